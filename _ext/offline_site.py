"""Sphinx extension of this book: keep the static site self-contained (it must work offline).

Jupyter Book 1 always loads sphinx-thebe, which adds scripts that fetch thebe from a CDN for live
code cells. The book has none (its notebooks are executed and tested ahead of time), and those
scripts are added twice, which is a JavaScript error in every page. This extension removes
sphinx-thebe's script hook before the build reads any document.
"""


def _drop_thebe(app, config):
    listeners = app.events.listeners.get("env-before-read-docs", [])
    for listener in list(listeners):
        if getattr(listener.handler, "__name__", "") == "init_thebe_core":
            app.disconnect(listener.id)


def setup(app):
    app.connect("config-inited", _drop_thebe, priority=900)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
