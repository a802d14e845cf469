"""The local web explorer of ``pendulab serve``: a page and a JSON API over the library.

:func:`create_app` builds the FastAPI app (:mod:`~pendulab.web.app`); the request handling
is plain functions: :mod:`~pendulab.web.parameters` reads a query, :mod:`~pendulab.web.limits`
bounds its work, :mod:`~pendulab.web.sampling` chooses what is drawn, :mod:`~pendulab.web.views`
renders the answers whose shapes :mod:`~pendulab.web.models` publishes. The page's own HTML, script and style live in ``static/``;
plotly.js (its "basic" bundle, MIT licence) ships there too, so the page works offline.
"""
from .app import create_app

__all__ = ["create_app"]
