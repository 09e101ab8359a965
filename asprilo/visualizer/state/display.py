"""Whether the viewer's window can open here, checked before Qt starts: Qt itself would
abort (exit 134) with a message that names no cause.

On Linux Qt draws windows through its xcb platform plugin, which needs a display
(``DISPLAY``, an X server answering there) and a set of X libraries of the system.  A user
who chose another platform (``QT_QPA_PLATFORM=offscreen``, ``wayland``, ``vnc``, ...) is
trusted.  No Qt module is imported here.
"""

from __future__ import annotations

import ctypes
import importlib.util
import os
import re
import socket
import sys
from collections.abc import Callable, Mapping
from pathlib import Path

#: the system libraries Qt needs (the PyQt5 wheel brings Qt itself), with their Debian and
#: Ubuntu packages: QtCore, QtGui, QtWidgets, QtNetwork, QtDBus, the offscreen and the xcb
#: platform plugins (``readelf -d`` lists them as NEEDED)
LIBRARIES = {
    "libglib-2.0.so.0": "libglib2.0-0", "libgthread-2.0.so.0": "libglib2.0-0", "libGL.so.1": "libgl1",
    "libfontconfig.so.1": "libfontconfig1", "libfreetype.so.6": "libfreetype6", "libdbus-1.so.3": "libdbus-1-3",
    "libgssapi_krb5.so.2": "libgssapi-krb5-2", "libX11.so.6": "libx11-6", "libXext.so.6": "libxext6",
    "libX11-xcb.so.1": "libx11-xcb1", "libxcb.so.1": "libxcb1", "libxcb-icccm.so.4": "libxcb-icccm4",
    "libxcb-image.so.0": "libxcb-image0", "libxcb-keysyms.so.1": "libxcb-keysyms1",
    "libxcb-randr.so.0": "libxcb-randr0", "libxcb-render.so.0": "libxcb-render0",
    "libxcb-render-util.so.0": "libxcb-render-util0", "libxcb-shape.so.0": "libxcb-shape0",
    "libxcb-shm.so.0": "libxcb-shm0", "libxcb-sync.so.1": "libxcb-sync1", "libxcb-xfixes.so.0": "libxcb-xfixes0",
    "libxcb-xinerama.so.0": "libxcb-xinerama0", "libxcb-xkb.so.1": "libxcb-xkb1",
    "libxkbcommon.so.0": "libxkbcommon0", "libxkbcommon-x11.so.0": "libxkbcommon-x11-0",
}
INSTALL = "sudo apt-get install " + " ".join(dict.fromkeys(LIBRARIES.values()))
HEADLESS = "for pictures and animations use --export FILE, or run with QT_QPA_PLATFORM=offscreen"
_MISSING = re.compile(r"(\S+\.so[.\d]*): cannot open shared object file")

Loader = Callable[[str], object]


def window_problem(environ: Mapping[str, str] = os.environ, load: Loader = ctypes.CDLL) -> str | None:
    """Why no window can open here (one line saying what to do), or ``None``."""
    platform = environ.get("QT_QPA_PLATFORM", "")
    if not sys.platform.startswith("linux") or (platform and not platform.startswith("xcb")):
        return None
    display = environ.get("DISPLAY", "")
    if not display:
        return f"no display to open a window on (DISPLAY is not set): {HEADLESS}"
    missing = missing_libraries(load)
    if missing:
        return (f"Qt cannot open a window: the system lacks {', '.join(missing)}; on Debian or Ubuntu: "
                f"{INSTALL}; or, without a window, {HEADLESS}")
    if not x_server_answers(display):
        return f"no X server answers on DISPLAY={display}: {HEADLESS}"
    return None


def missing_libraries(load: Loader = ctypes.CDLL) -> list[str]:
    """The system libraries Qt's xcb platform plugin cannot find (none when the plugin loads,
    or when this is not a PyQt5 wheel whose plugin can be found)."""
    plugin = xcb_plugin()
    if plugin is None:
        return []
    try:
        load(str(plugin))
        return []
    except OSError as error:
        first = _MISSING.search(str(error))
    missing = []
    for library in LIBRARIES:
        try:
            load(library)
        except OSError:
            missing.append(library)
    return missing or ([first.group(1)] if first else [f"a library of {plugin.name}"])


def xcb_plugin() -> Path | None:
    """Where PyQt5's xcb platform plugin is (without importing PyQt5)."""
    spec = importlib.util.find_spec("PyQt5")
    for folder in (spec.submodule_search_locations or []) if spec else []:
        for qt in ("Qt5", "Qt"):
            plugin = Path(folder, qt, "plugins", "platforms", "libqxcb.so")
            if plugin.exists():
                return plugin
    return None


def x_server_answers(display: str, seconds: float = 2.0) -> bool:
    """Whether something listens where ``DISPLAY`` points (``:N``, ``unix:N``, ``HOST:N``);
    ``True`` for a form this does not know (the X server will say)."""
    match = re.fullmatch(r"(?P<host>[^:/]*):(?P<number>\d+)(\.\d+)?", display)
    if match is None:
        return True
    host, number = match.group("host"), int(match.group("number"))
    if host in ("", "unix"):
        family, address = socket.AF_UNIX, f"/tmp/.X11-unix/X{number}"
        if not os.path.exists(address):
            address = f"\0/tmp/.X11-unix/X{number}"  # the abstract name some X servers use
    else:
        family, address = socket.AF_INET, (host, 6000 + number)
    try:
        with socket.socket(family, socket.SOCK_STREAM) as connection:
            connection.settimeout(seconds)
            connection.connect(address)
    except OSError:
        return False
    return True
