"""Find a Chromium-family browser for the site test (and anything else that drives the built site).

Looked for in this order, the first that exists wins:

1. the path in the environment variable ``MECHANISMS_BROWSER`` (it must exist if set);
2. the usual command names on ``PATH``: ``chromium``, ``chromium-browser``, ``google-chrome``,
   ``google-chrome-stable``, ``chrome``, ``microsoft-edge``, ``brave-browser``;
3. the usual install paths on Linux (Debian's and Ubuntu's packages, snap, Fedora's) and macOS
   (Google Chrome, Chromium, Microsoft Edge, Brave in ``/Applications`` and ``~/Applications``);
4. Playwright's own Chromium, if ``playwright install chromium`` put one in its cache.

:func:`find_browser` raises :class:`BrowserNotFound` listing everything it looked for.
"""

from __future__ import annotations

import os
import pathlib
import shutil
import sys

ENVIRONMENT_VARIABLE = "MECHANISMS_BROWSER"

NAMES = ("chromium", "chromium-browser", "google-chrome", "google-chrome-stable", "chrome", "microsoft-edge",
         "brave-browser")

PATHS = (
    "/usr/bin/chromium", "/usr/bin/chromium-browser", "/snap/bin/chromium", "/usr/lib/chromium/chromium",
    "/usr/lib64/chromium-browser/chromium-browser", "/usr/bin/google-chrome", "/opt/google/chrome/chrome",
    "/usr/bin/microsoft-edge", "/usr/bin/brave-browser",
    "/Applications/Google Chrome.app/Contents/MacOS/Google Chrome",
    "/Applications/Chromium.app/Contents/MacOS/Chromium",
    "/Applications/Microsoft Edge.app/Contents/MacOS/Microsoft Edge",
    "/Applications/Brave Browser.app/Contents/MacOS/Brave Browser",
    "~/Applications/Google Chrome.app/Contents/MacOS/Google Chrome",
    "~/Applications/Chromium.app/Contents/MacOS/Chromium",
)

INSTALL_HINT = ("install one: Debian/Ubuntu `apt-get install chromium`, Fedora `dnf install chromium`, macOS "
                "`brew install --cask chromium` or Google Chrome, any system `.venv/bin/playwright install "
                f"chromium`; or point {ENVIRONMENT_VARIABLE} at a Chromium-family browser")


class BrowserNotFound(RuntimeError):
    """No Chromium-family browser was found; the message lists what was looked for."""


def _playwright_chromium() -> pathlib.Path | None:
    """Playwright's own Chromium, if it is installed (its path even when the file is absent: None)."""
    try:
        from playwright.sync_api import sync_playwright
    except ImportError:
        return None
    try:
        with sync_playwright() as p:
            path = pathlib.Path(p.chromium.executable_path)
    except Exception:  # Playwright without its browser download, or no driver: nothing found here
        return None
    return path if path.is_file() else None


def find_browser(environ: dict[str, str] | None = None, search_path: str | None = None,
                 paths: tuple[str, ...] = PATHS, use_playwright: bool = True) -> pathlib.Path:
    """The path of a Chromium-family browser, or raise :class:`BrowserNotFound` saying what was looked for.

    Parameters
    ----------
    environ : dict, optional
        The environment (default ``os.environ``).
    search_path : str, optional
        The ``PATH`` to search the command names in (default: the environment's ``PATH``).
    paths : tuple of str
        Install paths to look at after the command names.
    use_playwright : bool
        Whether to look for Playwright's own Chromium last.
    """
    environ = dict(os.environ) if environ is None else environ
    looked = []
    chosen = environ.get(ENVIRONMENT_VARIABLE)
    if chosen:
        path = pathlib.Path(chosen).expanduser()
        if path.is_file():
            return path
        raise BrowserNotFound(f"{ENVIRONMENT_VARIABLE}={chosen} is set but there is no file there")
    looked.append(f"{ENVIRONMENT_VARIABLE} (not set)")
    search_path = environ.get("PATH", "") if search_path is None else search_path
    for name in NAMES:
        found = shutil.which(name, path=search_path)
        if found:
            return pathlib.Path(found)
    looked.append("the commands " + ", ".join(NAMES) + " on PATH")
    for candidate in paths:
        path = pathlib.Path(candidate).expanduser()
        if path.is_file():
            return path
    looked.append("the paths " + ", ".join(paths))
    if use_playwright:
        path = _playwright_chromium()
        if path is not None:
            return path
        looked.append("Playwright's own Chromium (`playwright install chromium`)")
    raise BrowserNotFound(f"no Chromium-family browser found on {sys.platform}; looked for: " + "; ".join(looked)
                          + ". " + INSTALL_HINT)
