"""``python -m pendulab``, and the ``pendulab`` command's entry point (:func:`run`)."""
import gc  # built in, loaded with the interpreter
import os  # loaded with the interpreter (by site)
import sys


def run() -> int:
    """:func:`pendulab.cli.main`; a signal (Ctrl+C, SIGTERM, SIGHUP, SIGQUIT) while the command
    line loads is one line too, and the status 128 + its number.

    Every import is inside (``signal`` loads ``enum``, ``core.interrupt`` loads ``threading``):
    before this function runs, only Python's start-up and the package's first lines (a few
    plain modules, no ``typing``) are left to Python's own handling of Ctrl+C.
    """
    # The commands' linear algebra is small (7 unknowns, sums of 3 columns): one BLAS thread
    # does it, with the same results. Each OpenBLAS (numpy's, scipy's) would start a worker
    # per further core, each spinning for tens of ms of CPU as the library loads. Before
    # numpy is imported; a setting of the user's own is kept.
    os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
    try:
        import signal

        from .core.interrupt import install, signal_of, word

        install()  # before the command line's imports: they take a while
        if hasattr(signal, "SIGXFSZ"):  # `ulimit -f`: a write past it fails with EFBIG (one line), not a kill
            signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
        from .core.streams import adopt_standard_streams

        adopt_standard_streams()  # before anything opens a file: a closed stdout is held, not reused
        from .core.environ import odd_numba_settings

        for note in odd_numba_settings():  # before numba's import reads them
            sys.stderr.write(note + "\n")
        from .cli import main

        code = main()
    except KeyboardInterrupt as exc:  # while the command line loaded, or just after the command
        try:
            signum, said = signal_of(exc), word(signal_of(exc))
        except NameError:  # Ctrl+C while core.interrupt itself loaded: Python's own handler, so SIGINT
            signum, said = 2, "interrupted"
        try:  # noqa: SIM105 (contextlib is not loaded yet)
            sys.stderr.write(f"pendulab: {said}\n")
        except (OSError, ValueError, AttributeError):
            pass  # standard error gone: silence
        code = 128 + signum
    import signal  # loaded, unless the Ctrl+C came while it loaded

    # The command is over and has said how: what is left is Python's shutdown, where a
    # signal would end the process by that signal instead (no line, another status).
    # Blocked from here, it stays pending until the process has exited with its status.
    from .core.interrupt import ENDING

    signal.pthread_sigmask(signal.SIG_BLOCK, set(ENDING))
    # Nor does the shutdown need the cycle collector: its last passes would examine and
    # free, one by one, every object the command made (after a report, over a tenth of
    # its CPU time), memory the system takes back at once when the process ends. Outputs
    # are written atomically and closed by then; Python flushes stdout and stderr itself.
    gc.freeze()
    # A daemon thread may still be compiling a kernel (serve's warm-up, when Ctrl+C comes
    # as the server starts): Python's shutdown would tear the interpreter down under LLVM,
    # which then aborts the process (SIGABRT after the line). Nothing is left to do but
    # flush: the process ends here, with its status.
    threading = sys.modules.get("threading")
    if threading is not None and any(t.daemon and t.is_alive() for t in threading.enumerate()):
        for stream in (sys.stdout, sys.stderr):
            try:  # noqa: SIM105 (as above)
                stream.flush()
            except Exception:
                pass
        os._exit(code)
    return code


if __name__ == "__main__":  # not when a tool imports it (the docs' module walk)
    sys.exit(run())
