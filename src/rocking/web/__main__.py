"""``python -m rocking.web [--host H] [--port P] [--timeout S] [--sweep-timeout S] [--max-upload-mb M]
[--max-duration S] [--max-jobs-per-client N]``: the same as ``rocking serve``."""

from __future__ import annotations

import argparse
import sys

from .server import serve, settings_from


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m rocking.web", description="Serve the rocking web app.")
    parser.add_argument("--host", default="127.0.0.1", help="address to listen on (default 127.0.0.1)")
    parser.add_argument("--port", type=int, default=8000, help="TCP port (default 8000; 0: any free port)")
    parser.add_argument("--timeout", type=float, default=120.0, help="longest run, s (default 120)")
    parser.add_argument("--sweep-timeout", type=float, default=600.0, help="longest design sweep, s (default 600)")
    parser.add_argument("--max-upload-mb", type=float, default=5.0, help="largest uploaded record, MB (default 5)")
    parser.add_argument("--max-duration", type=float, default=600.0,
                        help="longest simulated time of one run, s (default 600)")
    parser.add_argument("--max-jobs-per-client", type=int, default=2,
                        help="runs and sweeps one address may have in progress at once (default 2)")
    args = parser.parse_args(argv)
    try:
        settings = settings_from(args.timeout, args.sweep_timeout, args.max_upload_mb, max_duration=args.max_duration,
                                 max_jobs_per_client=args.max_jobs_per_client)
    except ValueError as exc:
        parser.error(str(exc))
    try:
        serve(args.host, args.port, settings)
    except OSError as exc:
        print(f"error: cannot listen on {args.host}:{args.port}: {exc.strerror or exc}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
