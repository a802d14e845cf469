"""The local web explorer of ``pendulab serve``: a page and a JSON API over the library.

:func:`create_app` builds the FastAPI app; :mod:`pendulab.web.api` holds the request
handling as plain functions. The page's own HTML, script and style live in ``static/``;
plotly.js is served from the installed ``plotly`` package, so the page works offline.
"""
from .app import create_app

__all__ = ["create_app"]
