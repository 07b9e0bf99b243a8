"""holoray live's windows under Xvfb, which runs no window manager, through
libX11 by ctypes (no other package needed): the tests' stand-in for a user
closing the window, and the guide's screenshot of it.

    xwindow.py close PREFIX [SECONDS]  ask the window whose title starts with PREFIX to close, as a
                                       window manager's close button does (WM_DELETE_WINDOW), again
                                       every half second until it is gone (as a user clicks again);
                                       exit 1 if no such window appeared, or it stayed, for SECONDS
                                       (default 30); print how many times it was asked
    xwindow.py wait PREFIX [SECONDS]   wait for such a window; print its title
    xwindow.py grab FILE.png           the whole screen, as X shows it, to an RGB PNG
"""
import ctypes
import ctypes.util
import struct
import sys
import time
import zlib

x11 = ctypes.cdll.LoadLibrary(ctypes.util.find_library("X11") or "libX11.so.6")
Window = ctypes.c_ulong
x11.XOpenDisplay.restype = ctypes.c_void_p
x11.XOpenDisplay.argtypes = [ctypes.c_char_p]
x11.XDefaultRootWindow.restype = Window
x11.XDefaultRootWindow.argtypes = [ctypes.c_void_p]
x11.XQueryTree.argtypes = [ctypes.c_void_p, Window, ctypes.POINTER(Window), ctypes.POINTER(Window),
                           ctypes.POINTER(ctypes.POINTER(Window)), ctypes.POINTER(ctypes.c_uint)]
x11.XFetchName.argtypes = [ctypes.c_void_p, Window, ctypes.POINTER(ctypes.c_char_p)]
x11.XInternAtom.restype = ctypes.c_ulong
x11.XInternAtom.argtypes = [ctypes.c_void_p, ctypes.c_char_p, ctypes.c_int]
x11.XSendEvent.argtypes = [ctypes.c_void_p, Window, ctypes.c_int, ctypes.c_long, ctypes.c_void_p]
x11.XFlush.argtypes = [ctypes.c_void_p]
x11.XFree.argtypes = [ctypes.c_void_p]
x11.XDefaultScreen.argtypes = [ctypes.c_void_p]
x11.XDisplayWidth.argtypes = [ctypes.c_void_p, ctypes.c_int]
x11.XDisplayHeight.argtypes = [ctypes.c_void_p, ctypes.c_int]
x11.XGetImage.restype = ctypes.c_void_p
x11.XGetImage.argtypes = [ctypes.c_void_p, Window, ctypes.c_int, ctypes.c_int, ctypes.c_uint, ctypes.c_uint,
                          ctypes.c_ulong, ctypes.c_int]


class XImage(ctypes.Structure):  # the leading fields of Xlib's XImage
    _fields_ = [("width", ctypes.c_int), ("height", ctypes.c_int), ("xoffset", ctypes.c_int), ("format", ctypes.c_int),
                ("data", ctypes.POINTER(ctypes.c_ubyte)), ("byte_order", ctypes.c_int), ("bitmap_unit", ctypes.c_int),
                ("bitmap_bit_order", ctypes.c_int), ("bitmap_pad", ctypes.c_int), ("depth", ctypes.c_int),
                ("bytes_per_line", ctypes.c_int), ("bits_per_pixel", ctypes.c_int)]


class ClientMessage(ctypes.Structure):  # XClientMessageEvent, format 32
    _fields_ = [("type", ctypes.c_int), ("serial", ctypes.c_ulong), ("send_event", ctypes.c_int),
                ("display", ctypes.c_void_p), ("window", Window), ("message_type", ctypes.c_ulong),
                ("format", ctypes.c_int), ("data", ctypes.c_long * 5)]


class Event(ctypes.Union):  # XEvent: 24 longs
    _fields_ = [("message", ClientMessage), ("pad", ctypes.c_long * 24)]


# A window may go while it is looked at (its program exiting): Xlib's
# default handler would end this script on the BadWindow that follows.
ERROR_HANDLER = ctypes.CFUNCTYPE(ctypes.c_int, ctypes.c_void_p, ctypes.c_void_p)(lambda display, error: 0)
x11.XSetErrorHandler.argtypes = [ctypes.c_void_p]
x11.XSetErrorHandler(ERROR_HANDLER)


def windows(display, window):
    root, parent = Window(), Window()
    children = ctypes.POINTER(Window)()
    count = ctypes.c_uint()
    if not x11.XQueryTree(display, window, ctypes.byref(root), ctypes.byref(parent), ctypes.byref(children),
                          ctypes.byref(count)):
        return
    found = [children[k] for k in range(count.value)]
    if children:
        x11.XFree(children)
    for w in found:
        yield w
        yield from windows(display, w)


def find(display, prefix):
    """The first window whose title starts with prefix, and its title."""
    for w in windows(display, x11.XDefaultRootWindow(display)):
        name = ctypes.c_char_p()
        if x11.XFetchName(display, w, ctypes.byref(name)) and name.value:
            title = name.value.decode(errors="replace")
            if title.startswith(prefix):
                return w, title
    return None, None


def wait_for(display, prefix, seconds):
    deadline = time.monotonic() + seconds
    while time.monotonic() < deadline:
        w, title = find(display, prefix)
        if w:
            return w, title
        time.sleep(0.1)
    sys.exit(f"xwindow.py: no window titled '{prefix}...' within {seconds} s")


def close(display, w):
    event = Event()
    event.message.type = 33  # ClientMessage
    event.message.window = w
    event.message.message_type = x11.XInternAtom(display, b"WM_PROTOCOLS", 0)
    event.message.format = 32
    event.message.data[0] = x11.XInternAtom(display, b"WM_DELETE_WINDOW", 0)
    x11.XSendEvent(display, w, 0, 0, ctypes.byref(event))
    x11.XFlush(display)


def grab(display, path):
    screen = x11.XDefaultScreen(display)
    width, height = x11.XDisplayWidth(display, screen), x11.XDisplayHeight(display, screen)
    image = ctypes.cast(x11.XGetImage(display, x11.XDefaultRootWindow(display), 0, 0, width, height,
                                      0xFFFFFFFF, 2), ctypes.POINTER(XImage)).contents  # ZPixmap
    if image.bits_per_pixel != 32:
        sys.exit(f"xwindow.py: a {image.bits_per_pixel}-bit screen (run Xvfb at depth 24)")
    rows = []
    for y in range(height):
        line = ctypes.string_at(ctypes.addressof(image.data.contents) + y * image.bytes_per_line, width * 4)
        rgb = bytearray(width * 3)
        rgb[0::3], rgb[1::3], rgb[2::3] = line[2::4], line[1::4], line[0::4]  # BGRX in memory
        rows.append(b"\0" + bytes(rgb))

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))

    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)) +
                chunk(b"IDAT", zlib.compress(b"".join(rows), 9)) + chunk(b"IEND", b""))


def main():
    what = sys.argv[1]
    display = x11.XOpenDisplay(None)
    if not display:
        sys.exit("xwindow.py: no X display")
    if what == "grab":
        grab(display, sys.argv[2])
        return
    seconds = float(sys.argv[3]) if len(sys.argv) > 3 else 30
    w, title = wait_for(display, sys.argv[2], seconds)
    if what != "close":
        print(title)
        return
    deadline, asked = time.monotonic() + seconds, 0
    while find(display, sys.argv[2])[0] == w:
        if time.monotonic() > deadline:
            sys.exit(f"xwindow.py: the window titled '{title}' stayed open for {seconds} s after {asked} requests to close")
        if asked == 0 or time.monotonic() > next_ask:
            close(display, w)
            asked, next_ask = asked + 1, time.monotonic() + 0.5
        time.sleep(0.05)
    print(f"xwindow.py: closed after {asked} request{'s' if asked > 1 else ''}")


if __name__ == "__main__":
    main()
