"""``pendulab serve``: the local web explorer."""
from __future__ import annotations

import contextlib
import errno
import ipaddress
import socket
from collections.abc import Callable

import click

from ..core.errors import shown
from ._common import integer

#: Ports tried after a busy one, to suggest a free one.
_PORTS_TRIED = 50
#: ``--per-address`` at most: the server's connections in all (``web.server.MAX_CONNECTIONS``,
#: not imported here: the server's module imports uvicorn).
_MOST_PER_ADDRESS = 512


def _bind(host: str, port: int) -> None:
    """Bind and release ``host:port`` once, so a failure is one clear line, not a traceback."""
    infos = socket.getaddrinfo(host, port, type=socket.SOCK_STREAM)
    with socket.socket(infos[0][0], socket.SOCK_STREAM) as s:
        s.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        s.bind(infos[0][4])


def free_port_after(host: str, port: int) -> int | None:
    """The first port after ``port`` that ``host`` can listen on, or None within 50 tries."""
    for p in range(port + 1, min(65536, port + 1 + _PORTS_TRIED)):
        try:
            _bind(host, p)
        except OSError:
            continue
        return p
    return None


def lan_addresses() -> list[str]:
    """This machine's IPv4 addresses other than loopback, as others on the network reach it.

    The address of the interface that routes outward (a UDP socket "connected" to a
    private address: nothing is sent), then those the host name resolves to.
    """
    found: list[str] = []
    with contextlib.suppress(OSError), socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as s:
        s.connect(("10.254.254.254", 9))
        found.append(s.getsockname()[0])
    with contextlib.suppress(OSError):
        found += socket.gethostbyname_ex(socket.gethostname())[2]
    out: list[str] = []
    for a in found:
        if not a.startswith("127.") and a != "0.0.0.0" and a not in out:
            out.append(a)
    return out


def bound_to(host: str) -> list[ipaddress.IPv4Address | ipaddress.IPv6Address]:
    """The addresses ``host`` names (``0`` and ``0.0.0.0``: every IPv4 interface)."""
    found = []
    for info in socket.getaddrinfo(host or None, None, type=socket.SOCK_STREAM):
        a = ipaddress.ip_address(str(info[4][0]).split("%")[0])
        if a not in found:
            found.append(a)
    return found


def every_interface(host: str) -> bool:
    return any(a.is_unspecified for a in bound_to(host))


def exposed(host: str) -> bool:
    """Whether binding ``host`` lets other computers connect (any address not loopback)."""
    return any(not a.is_loopback for a in bound_to(host))


def urls(host: str, port: int) -> list[str]:
    """The addresses to open the explorer at: for ``0.0.0.0``/``::``, this machine's LAN addresses."""
    if every_interface(host):
        return [f"http://{a}:{port}/" for a in lan_addresses()] + [f"http://127.0.0.1:{port}/"]
    shown = f"[{host}]" if ":" in host else host
    return [f"http://{shown}:{port}/"]


def allowed_hosts(host: str, extra: tuple[str, ...] = ()) -> list[str]:
    """The names a request's Host header may give: this computer's, the address bound (or
    for every interface, the LAN addresses printed), and ``extra`` (``--allow-host``)."""
    from ..web.guard import LOCAL_HOSTS

    names = [*LOCAL_HOSTS, host, *(str(a) for a in bound_to(host) if not a.is_unspecified), *extra]
    if every_interface(host):
        names += lan_addresses()
    return list(dict.fromkeys(n.lower() for n in names if n))


def _quietly(job: Callable[[], None]) -> None:
    """Run ``job``; a failure is one line on stderr (the warm-up only saves the first visitor time)."""
    try:
        job()
    except Exception as exc:  # whatever it is, the server serves on
        click.echo(f"pendulab serve: warm-up skipped ({type(exc).__name__}: {exc})", err=True)


#: Printed for every bind that other computers can reach.
EXPOSED = ("note: other computers on the network can open this explorer (there is no login), and run simulations "
           "on this machine; to serve this computer only: pendulab serve --host 127.0.0.1")


@click.command()
@click.option("--port", type=integer(1, 65535), default="8000", show_default=True, help="TCP port to listen on.")
@click.option("--host", default="127.0.0.1", show_default=True,
              help="Address to bind; the default serves this computer only (0.0.0.0: the whole network).")
@click.option("--allow-host", multiple=True, metavar="NAME",
              help="Another host name the page may be opened at (such as mybox.local); repeatable. "
                   "Requests naming any other host are refused.")
@click.option("--per-address", type=integer(1, _MOST_PER_ADDRESS), default=None, metavar="N",
              show_default="256, half the server's 512 connections; fewer under a low ulimit -n",
              help="Connections one address may hold at once. A class behind one NAT address shares them "
                   "(30 browsers hold about 180); past them a new connection closes that address's oldest "
                   "one still sending its request.")
def serve(port: int, host: str, allow_host: tuple[str, ...], per_address: int | None) -> None:
    """Start the web explorer: simulate, animate and plot the pendulum in the browser."""
    from ..core.extras import require

    for package in ("fastapi", "uvicorn", "orjson", "swagger_ui_bundle"):
        require(package, "pendulab serve")

    try:
        _bind(host, port)
    except (OSError, ValueError, UnicodeError) as exc:  # busy port, unknown host, a host that is no name
        reason = exc.strerror if isinstance(exc, OSError) and exc.strerror else "not a host name or address"
        if isinstance(exc, OSError) and exc.errno == errno.EADDRINUSE:
            free = free_port_after(host, port)
            reason += f"; port {free} is free: pendulab serve --port {free}" if free else ""
        raise click.BadParameter(f"cannot listen on {shown(host)}:{port}: {reason}", param_hint="--host/--port") from None

    import threading

    from ..core.interrupt import check_signals
    from ..engine.warm import warm_kernels
    from ..web import create_app
    from ..web.server import run
    from ..web.views import warm

    warm_kernels()  # the library's kernels compiled (or loaded) while the server starts
    # and the explorer's own (web/stream.py), through one tiny request.
    threading.Thread(target=_quietly, args=(warm,), name="pendulab-warm-web", daemon=True).start()
    where = urls(host, port)
    if len(where) == 1:
        click.echo(f"pendulab explorer: {where[0]}   (Ctrl+C to stop)", err=True)
    else:
        click.echo("pendulab explorer, open one of these (Ctrl+C to stop):", err=True)
        for u in where:
            click.echo(f"  {u}", err=True)
    if exposed(host):
        click.echo(EXPOSED, err=True)
    app = create_app(allowed_hosts(host, allow_host))
    # A Ctrl+C that came while the imports ran in a callback (interrupt.unraisable) ends the
    # command here; from the server's start, uvicorn's own handler holds it.
    check_signals()
    run(app, host, port, before=check_signals, max_per_client=per_address)
