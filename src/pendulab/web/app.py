"""The FastAPI app of ``pendulab serve``: the page, its static files and the JSON API.

Routes
------
``GET /``                     the explorer page (``static/index.html``)
``GET /static/{file}``        the page's own script and style
``GET /vendor/plotly.min.js`` plotly.js, read at run time from the installed ``plotly`` package
``GET /api/config``           methods in :data:`pendulab.taylor.METHODS` now, g presets, limits
``GET /api/period``           exact (AGM) and small-angle periods
``GET /api/simulate``         trajectory (thinned for plotting), exact period, estimates
``GET /api/convergence``      period estimates and their errors over a list of steps
``GET /api/trajectory.csv``   the trajectory as CSV

A bad or missing parameter gives status 422 and ``{"error": {"field", "value",
"allowed", "message"}}``; no input crashes the server.
"""
from __future__ import annotations

import logging
from collections.abc import Callable
from importlib import resources
from pathlib import Path
from typing import Any

from fastapi import FastAPI, Request
from fastapi.exceptions import RequestValidationError
from fastapi.responses import FileResponse, JSONResponse, Response
from starlette.exceptions import HTTPException as StarletteHTTPException

from ..errors import InputError
from . import api

STATIC = Path(__file__).parent / "static"
_log = logging.getLogger("pendulab.web")
_PAGES = {"index.html": "text/html", "app.js": "text/javascript", "style.css": "text/css", "favicon.svg": "image/svg+xml"}


def _plotly_js() -> Path:
    """plotly.js as shipped inside the installed Python package (never copied into this repo)."""
    return Path(str(resources.files("plotly") / "package_data" / "plotly.min.js"))


def error_body(exc: InputError) -> dict[str, Any]:
    value = exc.value if isinstance(exc.value, (int, float, str)) or exc.value is None else str(exc.value)
    return {"error": {"field": exc.name, "value": value, "allowed": exc.allowed, "message": str(exc)}}


def _json(call: Callable[[dict[str, str]], Any], request: Request) -> Response:
    try:
        return JSONResponse(call(dict(request.query_params)))
    except InputError as exc:
        return JSONResponse(error_body(exc), status_code=422)


def create_app() -> FastAPI:
    """The explorer as an ASGI app (``uvicorn.run(create_app())``)."""
    app = FastAPI(title="pendulab explorer", docs_url="/api/docs", redoc_url=None, openapi_url="/api/openapi.json")

    @app.exception_handler(RequestValidationError)
    async def _validation(request: Request, exc: RequestValidationError) -> JSONResponse:
        first = exc.errors()[0] if exc.errors() else {}
        field = str(first.get("loc", ["", "request"])[-1])
        return JSONResponse(error_body(InputError(field, "(invalid)", first.get("msg", "a valid value"))), status_code=422)

    @app.exception_handler(StarletteHTTPException)
    async def _http(request: Request, exc: StarletteHTTPException) -> JSONResponse:
        return JSONResponse({"error": {"message": str(exc.detail), "path": request.url.path}}, status_code=exc.status_code)

    @app.exception_handler(Exception)
    async def _bug(request: Request, exc: Exception) -> JSONResponse:  # a bug, not bad input: log it, keep serving
        _log.exception("internal error on %s", request.url)
        return JSONResponse({"error": {"message": f"internal error: {type(exc).__name__}"}}, status_code=500)

    # Plain `def` routes: FastAPI runs them in its thread pool, so the event loop keeps
    # answering while a simulation runs.
    @app.get("/api/config")
    def config() -> Response:
        return JSONResponse(api.config_view())

    @app.get("/api/period")
    def period(request: Request) -> Response:
        return _json(api.period_endpoint, request)

    @app.get("/api/simulate")
    def simulate(request: Request) -> Response:
        return _json(api.simulate_view, request)

    @app.get("/api/convergence")
    def convergence(request: Request) -> Response:
        return _json(api.convergence_view, request)

    @app.get("/api/trajectory.csv")
    def trajectory_csv(request: Request) -> Response:
        try:
            text, name = api.trajectory_csv(dict(request.query_params))
        except InputError as exc:
            return JSONResponse(error_body(exc), status_code=422)
        return Response(text, media_type="text/csv", headers={"Content-Disposition": f'attachment; filename="{name}"'})

    @app.get("/")
    def index() -> Response:
        return FileResponse(STATIC / "index.html", media_type="text/html", headers={"Cache-Control": "no-cache"})

    @app.get("/static/{name}")
    def static(name: str) -> Response:
        if name not in _PAGES:  # a fixed list: no path ever reaches the file system unchecked
            raise StarletteHTTPException(404, f"no static file {name!r}")
        return FileResponse(STATIC / name, media_type=_PAGES[name], headers={"Cache-Control": "no-cache"})

    @app.get("/vendor/plotly.min.js")
    def plotly_js() -> Response:
        return FileResponse(_plotly_js(), media_type="text/javascript", headers={"Cache-Control": "max-age=86400"})

    return app
