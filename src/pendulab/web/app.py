"""The FastAPI app of ``pendulab serve``: the page, its static files and the JSON API.

Routes
------
``GET /``                     the explorer page (``static/index.html``)
``GET /static/{file}``        the page's own script and style
``GET /vendor/plotly.min.js`` plotly.js's "basic" bundle (MIT licence, in ``static/``)
``GET /api/config``           the methods of :mod:`pendulab.core.methods`, g presets, limits, the page's words
``GET /api/period``           the AGM and small-angle periods
``GET /api/simulate``         what the page draws (min/max per column), exact motion, estimates, flags
``GET /api/convergence``      period estimates and their errors over a list of steps
``GET /api/motion``           the exact motion alone (the page's second pendulum)
``GET /api/period_curve``     T(alpha)/T0 from 0 to 179 deg, by the AGM and by the classical approximations
``GET /api/trajectory.csv``   the trajectory as CSV, streamed block by block
``GET /api/docs``             the API's documentation (Swagger UI from ``swagger-ui-bundle``: offline)

Every route answers ``HEAD`` as well; a request for any host but this computer (or the
addresses ``pendulab serve`` was bound to) gets 400 (:mod:`pendulab.web.guard`).
Every answer of 500 bytes or more is gzip-compressed when the client accepts it
(starlette's ``GZipMiddleware``; plotly.js compressed once, at level 9).
A bad or missing parameter gives status 422 and ``{"error": {"field", "value",
"allowed", "message"}}``; no input crashes the server.

The answers' shapes are :mod:`pendulab.web.models`, published in ``/api/openapi.json``.

Concurrency: every route is ``async``. The light ones (page, config, the AGM period) answer
on the event loop at once; each simulation runs in a pool of its own of
:data:`pendulab.web.limits.SIMULATION_SLOTS` threads at lower priority (nice +10), the one
limit on the cores. A request waiting for a slot is a queued work item awaited on the event
loop, holding no thread, so a class's worth of heavy requests never stops the page from
answering; the numba kernels release the GIL while they run. When a client goes away, its
queued work is dropped and its running work stops between two pieces of its kernel runs
(:func:`pendulab.core.interrupt.stop_when`).
"""
from __future__ import annotations

import asyncio
import contextlib
import functools
import gzip
import logging
import os
import threading
from collections.abc import AsyncIterator, Callable, Iterable, Mapping
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path
from typing import Annotated, Any

import orjson
from fastapi import FastAPI, Query, Request
from fastapi.exceptions import RequestValidationError
from fastapi.middleware.gzip import GZipMiddleware
from fastapi.responses import FileResponse, HTMLResponse, JSONResponse, Response, StreamingResponse
from starlette.exceptions import HTTPException as StarletteHTTPException

from ..core.errors import InputError
from ..core.interrupt import Stopped, stop_when
from . import guard, limits, models, parameters, views, words

STATIC = Path(__file__).parent / "static"
_log = logging.getLogger("pendulab.web")
_PAGES = {"index.html": "text/html", "app.js": "text/javascript", "lab.js": "text/javascript", "style.css": "text/css", "favicon.svg": "image/svg+xml"}


#: plotly.js's partial bundle "basic" (npm ``plotly.js-basic-dist-min`` 4.1.1, MIT licence in
#: ``static/plotly-basic.LICENSE.txt``): a quarter of the full bundle, every trace type the page uses.
PLOTLY_JS = STATIC / "plotly-basic.min.js"


@functools.cache
def _plotly_gzip() -> bytes:
    """plotly.js gzip-compressed at level 9, once (0.1 s): the middleware's level 6 costs that per request."""
    return gzip.compress(PLOTLY_JS.read_bytes(), compresslevel=9, mtime=0)


def _swagger_dir() -> Path:
    """Swagger UI's files as shipped in the ``swagger-ui-bundle`` package."""
    import swagger_ui_bundle  # type: ignore[import-untyped]

    return Path(swagger_ui_bundle.swagger_ui_path)


_SWAGGER = {"swagger-ui-bundle.js": "text/javascript", "swagger-ui.css": "text/css"}
# Swagger UI on the app's own schema, every file from this server.
_DOCS_PAGE = """<!doctype html>
<html lang="en"><head><meta charset="utf-8"><meta name="viewport" content="width=device-width, initial-scale=1">
<title>pendulab explorer API</title><link rel="icon" href="/static/favicon.svg" type="image/svg+xml">
<link rel="stylesheet" href="/vendor/swagger/swagger-ui.css"></head>
<body><div id="swagger-ui"></div><script src="/vendor/swagger/swagger-ui-bundle.js"></script>
<script>window.ui = SwaggerUIBundle({url: "/api/openapi.json", dom_id: "#swagger-ui", deepLinking: true,
presets: [SwaggerUIBundle.presets.apis], layout: "BaseLayout", validatorUrl: null});</script></body></html>
"""


def overflow(exc: ArithmeticError) -> InputError:
    """A value whose arithmetic left the doubles (a route that did not bound it): a 422 too."""
    return InputError("query", f"({type(exc).__name__})", "values whose arithmetic stays within the doubles "
                                                        "(|x| < 1.8e308; smaller lengths, times or g)")


def error_body(exc: InputError, lang: str = "en") -> dict[str, Any]:
    """A 422's body: the field (the query's name), the value as received, and the allowed range
    and the one-line message in ``lang`` (:func:`pendulab.web.words.message`)."""
    value = exc.value if isinstance(exc.value, (int, float, str)) or exc.value is None else str(exc.value)
    return {"error": {"field": exc.name, "value": value, "allowed": words.allowed(exc.allowed, lang),
                      "message": words.message(exc, lang)}}


def refusal(exc: InputError | ArithmeticError, params: Mapping[str, str]) -> JSONResponse:
    """The 422 of a bad input (its value as the query typed it) or of an overflow, in the
    request's language."""
    bad = parameters.as_typed(exc, params) if isinstance(exc, InputError) else overflow(exc)
    return JSONResponse(error_body(bad, words.safe_language(params)), status_code=422)


def _encode(body: Any) -> bytes:
    """JSON by orjson: several times faster than ``json`` on long float lists; floats in the
    shortest form that reads back to the same double; a non-finite one would be ``null``."""
    return orjson.dumps(body, option=orjson.OPT_SERIALIZE_NUMPY)


def _lower_priority() -> None:
    """Run this worker thread at nice +10, so the event loop (nice 0) gets a core at once.

    On Linux the nice value is per thread. Elsewhere, or where refused, nothing changes.
    """
    with contextlib.suppress(AttributeError, OSError):
        os.setpriority(os.PRIO_PROCESS, threading.get_native_id(), 10)


class _Slots:
    """The simulation slots: a pool of ``total`` worker threads of their own, at low priority.

    A request waiting for a slot is a queued work item awaited on the event loop: it holds
    no thread, neither the event loop nor the thread pool that serves files.
    """

    def __init__(self, total: int):
        self.total = total
        self._pool: ThreadPoolExecutor | None = None

    @property
    def pool(self) -> ThreadPoolExecutor:
        if self._pool is None:
            self._pool = ThreadPoolExecutor(self.total, thread_name_prefix="pendulab-sim", initializer=_lower_priority)
        return self._pool

    async def run(self, fn: Callable[..., Any], *args: Any) -> Any:
        return await asyncio.get_running_loop().run_in_executor(self.pool, fn, *args)

    async def run_while_connected(self, request: Request, fn: Callable[[threading.Event], Any]) -> Any:
        """``fn(stop)`` in a slot; if the client disconnects first, ``stop`` is set (and a
        queued ``fn`` never starts). Returns ``fn``'s result, or None when the client has gone."""
        stop = threading.Event()
        work = asyncio.ensure_future(self.run(fn, stop))
        gone = asyncio.ensure_future(_disconnected(request))
        try:
            await asyncio.wait((work, gone), return_when=asyncio.FIRST_COMPLETED)
        finally:
            gone.cancel()
        if not work.done():
            stop.set()
            work.cancel()  # a queued item is dropped; a running one sees stop at its next piece
            return None
        return work.result()


async def _disconnected(request: Request) -> None:
    """Return when the client of ``request`` (a GET, whose body is read) disconnects."""
    while (await request.receive())["type"] != "http.disconnect":
        pass


def _given(params: dict[str, str | None]) -> dict[str, str]:
    """The query parameters that were sent (the library's parsers judge their text)."""
    return {k: v for k, v in params.items() if v is not None}


# Typed query parameters: OpenAPI lists them; their text is parsed by pendulab.core.inputs, the
# CLI's parser, so a value is judged the same way in the page and in a terminal.
Length = Annotated[str | None, Query(description="Pendulum length l > 0, m: 3.5, 1e-2, 7/2")]
Amplitude = Annotated[str | None, Query(description="Amplitude in [0, pi): 0.785, pi/4, 4pi/5, 144deg, 144°")]
Unit = Annotated[str | None, Query(description="rad (default) or deg: the unit of a plain-number amplitude")]
Gravity = Annotated[str | None, Query(description="g > 0, m/s^2 (default 9.80665)")]
Step = Annotated[str | None, Query(description="Step h > 0, s: 1e-3")]
TMax = Annotated[str | None, Query(description="End time t_max > step, s: 20")]
MethodName = Annotated[str | None, Query(description="Integrator: taylor2 (default), rk4, verlet, taylor:P (P in 1..30)")]
Points = Annotated[str | None, Query(description="At most this many points returned (evenly thinned), 2..1000000")]
Omega0 = Annotated[str | None, Query(description="Initial angular velocity theta'(0), rad/s (default 0: "
                                            "released at rest); with enough the pendulum goes over the top")]
Columns = Annotated[str | None, Query(description="CSV columns: state (t, theta, omega; default) or all "
                                             "(also theta_exact, omega_exact, the global error, the energy error)")]
Lang = Annotated[str | None, Query(description="The language of the words: en (default) or pt")]
Damping = Annotated[str | None, Query(description="gamma >= 0, 1/s (default 0): the damping term gamma theta' of "
                                             "theta'' = -(g/l) sin(theta) - gamma theta' - beta theta'|theta'|")]
Drag = Annotated[str | None, Query(description="beta >= 0, 1/rad (default 0): the drag term beta theta'|theta'|")]
Mass = Annotated[str | None, Query(description="The bob's mass m > 0, kg (default 1): the energies in J, not the motion")]
Steps = Annotated[str | None, Query(description="Steps h, comma-separated, 1 to 40 (default 13 steps from 0.1 to 1e-4)")]


def create_app(allowed_hosts: Iterable[str] = guard.LOCAL_HOSTS) -> FastAPI:
    """The explorer as an ASGI app (``uvicorn.run(create_app())``).

    ``allowed_hosts``: the host names and addresses a request's ``Host`` header may name
    (:class:`pendulab.web.guard.Guard`); others get status 400.
    """
    # OpenAPI 3.0 labelling: the Swagger UI that swagger-ui-bundle ships (4.x) reads 3.0 only.
    app = FastAPI(title="pendulab explorer", docs_url=None, redoc_url=None, openapi_url="/api/openapi.json")
    app.openapi_version = "3.0.3"
    # Compressed answers: the page's script and a simulation's JSON are mostly text and digits.
    # Inside the guard, so a HEAD answer carries the GET's compressed headers.
    app.add_middleware(GZipMiddleware, minimum_size=500, compresslevel=6)
    app.add_middleware(guard.Guard, allowed_hosts=allowed_hosts)

    @app.exception_handler(RequestValidationError)
    async def _validation(request: Request, exc: RequestValidationError) -> JSONResponse:
        first = exc.errors()[0] if exc.errors() else {}
        field = str(first.get("loc", ["", "request"])[-1])
        lang = words.safe_language(request.query_params)
        why = first.get("msg", "a valid value") if lang == "en" else "a valid value"  # pydantic's words are English
        return JSONResponse(error_body(InputError(field, "(invalid)", why), lang), status_code=422)

    @app.exception_handler(StarletteHTTPException)
    async def _http(request: Request, exc: StarletteHTTPException) -> JSONResponse:
        return JSONResponse({"error": {"message": str(exc.detail), "path": request.url.path}}, status_code=exc.status_code)

    @app.exception_handler(Exception)
    async def _bug(request: Request, exc: Exception) -> JSONResponse:  # a bug, not bad input: log it, keep serving
        _log.exception("internal error on %s", request.url)
        return JSONResponse({"error": {"message": f"internal error: {type(exc).__name__}"}}, status_code=500)

    # The page's own files, read once: answered from memory on the event loop, no thread needed.
    pages = {name: (STATIC / name).read_bytes() for name in _PAGES}
    slots = _Slots(limits.SIMULATION_SLOTS)
    app.state.slots = slots

    async def heavy(request: Request, call: Callable[..., Any], query: dict[str, str | None]) -> Response:
        """Parse, compute and encode in a worker thread, within the simulation slots; stopped
        when the client goes away."""
        params = _given(query)

        def work(stop: threading.Event) -> Response:
            try:
                with stop_when(stop):
                    return Response(_encode(call(params)), media_type="application/json")
            except (InputError, OverflowError, FloatingPointError) as exc:
                return refusal(exc, params)
            except Stopped:
                return Response(status_code=499)  # nobody reads it

        answer = await slots.run_while_connected(request, work)
        return Response(status_code=499) if answer is None else answer

    def light(call: Callable[[dict[str, str]], Any], query: dict[str, str | None]) -> Response:
        params = _given(query)
        try:
            return JSONResponse(call(params))
        except (InputError, OverflowError, FloatingPointError) as exc:
            return refusal(exc, params)

    bad: dict[int | str, dict[str, Any]] = {422: {"model": models.ErrorAnswer, "description": "a bad parameter, named"}}

    @app.get("/api/config", response_model=models.ConfigAnswer, responses=bad)
    async def config(lang: Lang = None) -> Response:
        return light(views.config_view, {"lang": lang})

    @app.get("/api/period", response_model=models.PeriodAnswer, responses=bad)
    async def period(length: Length = None, amplitude: Amplitude = None, unit: Unit = None,
                     g: Gravity = None, lang: Lang = None) -> Response:
        # The periods of one pendulum (periods(), a fraction of a millisecond), answered on the event loop.
        return light(views.period_endpoint, {"length": length, "amplitude": amplitude, "unit": unit, "g": g,
                                             "lang": lang})

    @app.get("/api/simulate", response_model=models.SimulateAnswer, responses=bad)
    async def simulate(request: Request, length: Length = None, amplitude: Amplitude = None, unit: Unit = None, g: Gravity = None,
                       step: Step = None, t_max: TMax = None, method: MethodName = None,
                       points: Points = None, omega0: Omega0 = None, lang: Lang = None,
                       damping: Damping = None, drag: Drag = None, mass: Mass = None) -> Response:
        return await heavy(request, views.simulate_view, {"length": length, "amplitude": amplitude, "unit": unit, "g": g,
                                               "step": step, "t_max": t_max, "method": method, "points": points,
                                               "omega0": omega0, "lang": lang, "damping": damping, "drag": drag,
                                               "mass": mass})

    @app.get("/api/convergence", response_model=models.ConvergenceAnswer, responses=bad)
    async def convergence(request: Request, length: Length = None, amplitude: Amplitude = None, unit: Unit = None, g: Gravity = None,
                          method: MethodName = None, steps: Steps = None, lang: Lang = None) -> Response:
        return await heavy(request, views.convergence_view, {"length": length, "amplitude": amplitude, "unit": unit, "g": g,
                                                  "method": method, "steps": steps, "lang": lang})

    @app.get("/api/motion", response_model=models.MotionAnswer, responses=bad)
    async def motion(length: Length = None, amplitude: Amplitude = None, unit: Unit = None, g: Gravity = None,
                     t_max: TMax = None, lang: Lang = None) -> Response:
        # At most 8000 Jacobi evaluations: milliseconds, on the event loop.
        return light(views.motion_view, {"length": length, "amplitude": amplitude, "unit": unit, "g": g, "t_max": t_max,
                                         "lang": lang})

    @app.get("/api/period_curve", response_model=models.PeriodCurveAnswer)
    async def period_curve() -> Response:
        return JSONResponse(views.period_curve_view())

    csv: dict[int | str, dict[str, Any]] = {200: {"content": {"text/csv": {"schema": {"type": "string"}}},
                 "description": "t,theta,omega in s, rad, rad/s (columns=all: and theta_exact, omega_exact, "
                 "theta_error in rad, rad/s, rad and energy_error in m g l): one row per kept step, full precision"}}

    @app.get("/api/trajectory.csv", response_class=StreamingResponse, responses=csv | bad)
    async def trajectory_csv(length: Length = None, amplitude: Amplitude = None, unit: Unit = None,
                             g: Gravity = None, step: Step = None, t_max: TMax = None, method: MethodName = None,
                             points: Points = None, columns: Columns = None, omega0: Omega0 = None,
                             damping: Damping = None, drag: Drag = None, mass: Mass = None,
                             lang: Lang = None) -> Response:
        params = _given({"length": length, "amplitude": amplitude, "unit": unit, "g": g, "step": step, "t_max": t_max,
                         "method": method, "points": points, "columns": columns, "omega0": omega0,
                         "damping": damping, "drag": drag, "mass": mass, "lang": lang})
        try:
            blocks, name = views.trajectory_csv(params)
        except InputError as exc:  # the CSV has no words; its refusal is in the language asked
            return refusal(exc, params)

        async def stream() -> AsyncIterator[str]:
            # One block per slot: a slow download never holds a slot while the client reads.
            done = object()
            while (block := await slots.run(next, blocks, done)) is not done:
                yield block

        return StreamingResponse(stream(), media_type="text/csv",
                                 headers={"Content-Disposition": f'attachment; filename="{name}"'})

    @app.get("/api/docs", include_in_schema=False)
    async def docs() -> HTMLResponse:
        return HTMLResponse(_DOCS_PAGE)

    @app.get("/vendor/swagger/{name}", include_in_schema=False)
    async def swagger_file(name: str) -> Response:
        if name not in _SWAGGER:
            raise StarletteHTTPException(404, f"no file {name!r}")
        return FileResponse(_swagger_dir() / name, media_type=_SWAGGER[name], headers={"Cache-Control": "max-age=86400"})

    @app.get("/", include_in_schema=False)
    async def index() -> Response:
        return Response(pages["index.html"], media_type="text/html", headers={"Cache-Control": "no-cache"})

    @app.get("/static/{name}", include_in_schema=False)
    async def static(name: str) -> Response:
        if name not in _PAGES:  # a fixed list: no path ever reaches the file system unchecked
            raise StarletteHTTPException(404, f"no static file {name!r}")
        return Response(pages[name], media_type=_PAGES[name], headers={"Cache-Control": "no-cache"})

    @app.get("/vendor/plotly.min.js", include_in_schema=False)
    async def plotly_js(request: Request) -> Response:
        headers = {"Cache-Control": "max-age=86400", "Vary": "Accept-Encoding"}
        if "gzip" in request.headers.get("accept-encoding", ""):  # compressed once, not per request
            return Response(_plotly_gzip(), media_type="text/javascript", headers=headers | {"Content-Encoding": "gzip"})
        return Response(PLOTLY_JS.read_bytes(), media_type="text/javascript", headers=headers)

    return app
