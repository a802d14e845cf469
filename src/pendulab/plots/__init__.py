"""matplotlib renderings of computed results.

Each function takes an ``ax`` (or makes a figure), draws results already computed by
the library, and returns what it drew. Nothing here computes a number.
"""
