"""Serve the web app on a local port: ``rocking serve`` and ``python -m rocking.web``.

A threaded WSGI server (Werkzeug's, which Flask brings): every request has its own thread, and
every computation its own worker process (:mod:`rocking.web.jobs`), so users do not wait for each
other. Meant for a workstation or a trusted network: there are no accounts.
"""

from __future__ import annotations

import ipaddress
import signal
import socket
import sys
import threading
from collections.abc import Mapping
from typing import Any

__all__ = ["LOOPBACK_NAMES", "is_loopback", "make_server", "serve", "settings_from"]

#: Host names accepted in requests when the server listens on a loopback address (against DNS
#: rebinding: another site's page cannot reach the app through a name it controls).
LOOPBACK_NAMES = ("localhost", "127.0.0.1", "::1")


def settings_from(timeout: float = 120.0, sweep_timeout: float = 600.0, max_upload_mb: float = 5.0, *,
                  max_duration: float = 600.0, max_jobs_per_client: int = 2) -> dict[str, Any]:
    """App settings (see :data:`rocking.web.app.DEFAULTS`) from the command-line options.

    Parameters
    ----------
    timeout, sweep_timeout : float
        Longest run and design sweep, s.
    max_upload_mb : float
        Largest uploaded record, MB.
    max_duration : float
        Longest simulated time of one run, s.
    max_jobs_per_client : int
        Runs and sweeps one client address may have in progress at once.

    Raises
    ------
    ValueError
        If a value is not positive; the message names the option.
    """
    for name, value in (("--timeout", timeout), ("--sweep-timeout", sweep_timeout), ("--max-upload-mb", max_upload_mb),
                        ("--max-duration", max_duration), ("--max-jobs-per-client", max_jobs_per_client)):
        if not value > 0:
            raise ValueError(f"{name} must be positive, got {value:g}")
    return {"RUN_TIMEOUT": float(timeout), "SWEEP_TIMEOUT": float(sweep_timeout),
            "MAX_UPLOAD": int(max_upload_mb * 1024 * 1024), "MAX_DURATION": float(max_duration),
            "MAX_JOBS_PER_CLIENT": int(max_jobs_per_client)}


def is_loopback(host: str) -> bool:
    """True for localhost and the loopback addresses (127.0.0.0/8, ::1)."""
    if host == "localhost":
        return True
    try:
        return ipaddress.ip_address(host.strip("[]")).is_loopback
    except ValueError:
        return False


def make_server(host: str = "127.0.0.1", port: int = 8000, settings: Mapping[str, Any] | None = None):
    """The app and a threaded WSGI server bound to ``host:port`` (port 0: any free port).

    Returns
    -------
    server : werkzeug.serving.BaseWSGIServer
        ``server.port`` is the port bound; ``server.serve_forever()`` runs it.
    app : flask.Flask
    """
    from werkzeug.serving import get_sockaddr, select_address_family
    from werkzeug.serving import make_server as _make_server

    from .app import create_app

    # Bind here, so that a port in use is an OSError for the caller (Werkzeug would print its own
    # message and exit), then hand the socket to the server.
    family = select_address_family(host, port)
    sock = socket.socket(family, socket.SOCK_STREAM)
    try:
        sock.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        sock.bind(get_sockaddr(host, int(port), family))
        sock.listen(128)
    except BaseException:
        sock.close()
        raise
    opts = dict(settings or {})
    if is_loopback(host):
        names = set(LOOPBACK_NAMES) | {host.strip("[]")}
        opts.setdefault("ALLOWED_HOSTS", sorted(names))
    try:
        app = create_app(opts)
    except BaseException:
        sock.close()
        raise
    try:
        server = _make_server(host, port, app, threaded=True, fd=sock.fileno())
    except BaseException:
        app.extensions["rocking"].shutdown()
        raise
    finally:
        sock.close()  # the server holds its own duplicate of the socket
    return server, app


def _interrupt(signum, frame) -> None:
    raise KeyboardInterrupt


def serve(host: str = "127.0.0.1", port: int = 8000, settings: Mapping[str, Any] | None = None) -> None:
    """Serve the app until interrupted (Ctrl+C), then stop the workers and remove the run files.

    Prints ``rocking web app: http://HOST:PORT/`` on stdout once it listens.

    Raises
    ------
    OSError
        If the address cannot be bound (e.g. the port is in use).
    """
    server, app = make_server(host, port, settings)
    state = app.extensions["rocking"]
    state.runner.warm_up()
    if threading.current_thread() is threading.main_thread():
        # `kill` (SIGTERM) stops the server as Ctrl+C does: workers stopped, files removed
        signal.signal(signal.SIGTERM, _interrupt)
    shown = f"[{host}]" if ":" in host else host
    print(f"rocking web app: http://{shown}:{server.port}/  (Ctrl+C to stop)", flush=True)
    if not is_loopback(host):
        print(
            f"warning: listening on {host}: anyone who can reach this address can run simulations "
            "(there are no accounts)",
            file=sys.stderr,
            flush=True,
        )
    try:
        server.serve_forever()
    except KeyboardInterrupt:
        pass
    finally:
        server.server_close()
        state.shutdown()
