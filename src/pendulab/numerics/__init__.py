"""The numerical methods as pure functions: each returns a frozen ``Result`` or read-only
arrays, never prints, plots or reads a file. Above ``engine`` and ``core``."""
