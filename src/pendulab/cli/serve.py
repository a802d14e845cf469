"""``pendulab serve``: the local web explorer."""
from __future__ import annotations

import click

from ..inputs import shown
from ._common import integer


@click.command()
@click.option("--port", type=integer(1, 65535), default="8000", show_default=True, help="TCP port to listen on.")
@click.option("--host", default="127.0.0.1", show_default=True,
              help="Address to bind; the default serves this computer only (0.0.0.0: the whole network).")
def serve(port: int, host: str) -> None:
    """Start the web explorer: simulate, animate and plot the pendulum in the browser."""
    import socket

    from .._extras import require

    for package in ("fastapi", "uvicorn", "plotly"):
        require(package, "pendulab serve")

    # Bind once here so a busy port or an unknown host is one clear line, not a uvicorn traceback.
    try:
        infos = socket.getaddrinfo(host, port, type=socket.SOCK_STREAM)
        with socket.socket(infos[0][0], socket.SOCK_STREAM) as s:
            s.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
            s.bind(infos[0][4])
    except (OSError, ValueError, UnicodeError) as exc:  # busy port, unknown host, a host that is no name
        reason = exc.strerror if isinstance(exc, OSError) and exc.strerror else "not a host name or address"
        raise click.BadParameter(f"cannot listen on {shown(host)}:{port}: {reason}", param_hint="--host/--port") from None

    import uvicorn

    from .._warm import warm_kernels
    from ..web import create_app

    warm_kernels()  # the first request finds the kernels compiled

    where = f"[{host}]" if ":" in host else host
    click.echo(f"pendulab explorer: http://{where}:{port}/   (Ctrl+C to stop)", err=True)
    uvicorn.run(create_app(), host=host, port=port, log_level="warning")
