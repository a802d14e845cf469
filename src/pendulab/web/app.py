"""The FastAPI app of ``pendulab serve``: the page, its static files and the JSON API.

Routes
------
``GET /``                     the explorer page (``static/index.html``)
``GET /static/{file}``        the page's own script and style
``GET /vendor/plotly.min.js`` plotly.js, read at run time from the installed ``plotly`` package
``GET /api/config``           the methods of :mod:`pendulab.methods` now, g presets, limits
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
from typing import Annotated, Any

from fastapi import FastAPI, Query, Request
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


def _json(call: Callable[[dict[str, str]], Any], params: dict[str, str | None]) -> Response:
    try:
        return JSONResponse(call(_given(params)))
    except InputError as exc:
        return JSONResponse(error_body(exc), status_code=422)


def _given(params: dict[str, str | None]) -> dict[str, str]:
    """The query parameters that were sent (the library's parsers judge their text)."""
    return {k: v for k, v in params.items() if v is not None}


# Typed query parameters: OpenAPI lists them; their text is parsed by pendulab.inputs, the
# CLI's parser, so a value is judged the same way in the page and in a terminal.
Length = Annotated[str | None, Query(description="Pendulum length l > 0, m: 3.5, 1e-2, 7/2")]
Amplitude = Annotated[str | None, Query(description="Amplitude in [0, pi): 0.785, pi/4, 4pi/5, 144deg, 144°")]
Unit = Annotated[str | None, Query(description="rad (default) or deg: the unit of a plain-number amplitude")]
Gravity = Annotated[str | None, Query(description="g > 0, m/s^2 (default 9.80665)")]
Step = Annotated[str | None, Query(description="Step h > 0, s: 1e-3")]
TMax = Annotated[str | None, Query(description="End time t_max > step, s: 20")]
MethodName = Annotated[str | None, Query(description="Integrator: taylor2 (default), rk4, verlet, taylor:P (P in 1..30)")]
Points = Annotated[str | None, Query(description="At most this many points returned (evenly thinned), 2..1000000")]
Steps = Annotated[str | None, Query(description="Steps h, comma-separated, 1 to 40 (default 13 steps from 0.1 to 1e-4)")]


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
    def period(length: Length = None, amplitude: Amplitude = None, unit: Unit = None, g: Gravity = None) -> Response:
        return _json(api.period_endpoint, {"length": length, "amplitude": amplitude, "unit": unit, "g": g})

    @app.get("/api/simulate")
    def simulate(length: Length = None, amplitude: Amplitude = None, unit: Unit = None, g: Gravity = None,
                 step: Step = None, t_max: TMax = None, method: MethodName = None, points: Points = None) -> Response:
        return _json(api.simulate_view, {"length": length, "amplitude": amplitude, "unit": unit, "g": g,
                                             "step": step, "t_max": t_max, "method": method, "points": points})

    @app.get("/api/convergence")
    def convergence(length: Length = None, amplitude: Amplitude = None, unit: Unit = None, g: Gravity = None,
                    method: MethodName = None, steps: Steps = None) -> Response:
        return _json(api.convergence_view, {"length": length, "amplitude": amplitude, "unit": unit, "g": g,
                                                "method": method, "steps": steps})

    @app.get("/api/trajectory.csv")
    def trajectory_csv(length: Length = None, amplitude: Amplitude = None, unit: Unit = None, g: Gravity = None,
                       step: Step = None, t_max: TMax = None, method: MethodName = None,
                       points: Points = None) -> Response:
        params = {"length": length, "amplitude": amplitude, "unit": unit, "g": g, "step": step, "t_max": t_max,
                  "method": method, "points": points}
        try:
            text, name = api.trajectory_csv(_given(params))
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
