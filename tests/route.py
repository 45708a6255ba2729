"""The route of a job's data through the package's modules: their order and a tracer."""

import sys

#: The modules of a sweep and of a study, top to bottom: each imports and calls only modules below it.
TOP_TO_BOTTOM = ("fem_tether.commands.pipeline", "fem_tether.jobs.sweep", "fem_tether.jobs.study.driver",
                 "fem_tether.jobs.runner", "fem_tether.jobs.sweep_tasks", "fem_tether.jobs.study.tasks",
                 "fem_tether.jobs.sweepfile", "fem_tether.jobs.evaluate", "fem_tether.jobs.study.parts",
                 "fem_tether.jobs.store", "fem_tether.jobs.schedule", "fem_tether.jobs.job")


#: The layers the main job's data goes through (the solvers below them are not the sweep's).
ROUTE = ("fem_tether.commands", "fem_tether.jobs", "fem_tether.io", "fem_tether.core")


def calls_between_modules(run) -> list[tuple[str, str, bool]]:
    """(caller, callee, callee already on the stack) for every call of ``run()``
    from one module of :data:`ROUTE` into another (sys.setprofile)."""
    stack, calls = [], []

    def profile(frame, event, arg):
        if event == "call":
            module = frame.f_globals.get("__name__", "")
            ours = [m for m in stack if m.startswith(ROUTE)]
            if module.startswith(ROUTE) and ours and ours[-1] != module:
                calls.append((ours[-1], module, module in ours))
            stack.append(module)
        elif event == "return" and stack:
            stack.pop()
    sys.setprofile(profile)
    try:
        run()
    finally:
        sys.setprofile(None)
    return calls
