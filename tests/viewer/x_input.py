#!/usr/bin/env python3
"""Real input for the interactive viewer: X events through the XTEST extension (libXtst, as
a user's mouse and keyboard make them) and pictures of the screen (XGetImage), with ctypes
only. Used by the viewer tests that need events the viewer reads from the X server itself:
a drag that happens while a slow frame is drawn, a key press that starts a morph."""
import ctypes
import ctypes.util
import os
import time

_x11 = ctypes.CDLL(ctypes.util.find_library("X11") or "libX11.so.6")
_xtst = ctypes.CDLL(ctypes.util.find_library("Xtst") or "libXtst.so.6")
_x11.XOpenDisplay.restype = ctypes.c_void_p
_x11.XOpenDisplay.argtypes = [ctypes.c_char_p]
_x11.XDefaultRootWindow.restype = ctypes.c_ulong
_x11.XDefaultRootWindow.argtypes = [ctypes.c_void_p]
_x11.XKeysymToKeycode.restype = ctypes.c_ubyte
_x11.XKeysymToKeycode.argtypes = [ctypes.c_void_p, ctypes.c_ulong]
_x11.XStringToKeysym.restype = ctypes.c_ulong
_x11.XStringToKeysym.argtypes = [ctypes.c_char_p]
_x11.XFlush.argtypes = [ctypes.c_void_p]
_x11.XSync.argtypes = [ctypes.c_void_p, ctypes.c_int]
_x11.XGetImage.restype = ctypes.c_void_p
_x11.XGetImage.argtypes = [ctypes.c_void_p, ctypes.c_ulong, ctypes.c_int, ctypes.c_int,
                           ctypes.c_uint, ctypes.c_uint, ctypes.c_ulong, ctypes.c_int]
_x11.XGetPixel.restype = ctypes.c_ulong
_x11.XGetPixel.argtypes = [ctypes.c_void_p, ctypes.c_int, ctypes.c_int]
_xtst.XTestFakeMotionEvent.argtypes = [ctypes.c_void_p, ctypes.c_int, ctypes.c_int,
                                       ctypes.c_int, ctypes.c_ulong]
_xtst.XTestFakeButtonEvent.argtypes = [ctypes.c_void_p, ctypes.c_uint, ctypes.c_int,
                                       ctypes.c_ulong]
_xtst.XTestFakeKeyEvent.argtypes = [ctypes.c_void_p, ctypes.c_uint, ctypes.c_int,
                                    ctypes.c_ulong]


class _XImage(ctypes.Structure):
    _fields_ = [("width", ctypes.c_int), ("height", ctypes.c_int), ("xoffset", ctypes.c_int),
                ("format", ctypes.c_int), ("data", ctypes.POINTER(ctypes.c_ubyte)),
                ("byte_order", ctypes.c_int), ("bitmap_unit", ctypes.c_int),
                ("bitmap_bit_order", ctypes.c_int), ("bitmap_pad", ctypes.c_int),
                ("depth", ctypes.c_int), ("bytes_per_line", ctypes.c_int),
                ("bits_per_pixel", ctypes.c_int)]


class Display:
    def __init__(self, name=None):
        self.d = _x11.XOpenDisplay((name or os.environ["DISPLAY"]).encode())
        if not self.d:
            raise RuntimeError("cannot open the X display")
        self.root = _x11.XDefaultRootWindow(self.d)

    def _flush(self):
        _x11.XSync(self.d, 0)

    def move(self, x, y):
        _xtst.XTestFakeMotionEvent(self.d, -1, int(x), int(y), 0)
        self._flush()

    def button(self, down, button=1):
        _xtst.XTestFakeButtonEvent(self.d, button, 1 if down else 0, 0)
        self._flush()

    def key(self, name):
        code = _x11.XKeysymToKeycode(self.d, _x11.XStringToKeysym(name.encode()))
        _xtst.XTestFakeKeyEvent(self.d, code, 1, 0)
        _xtst.XTestFakeKeyEvent(self.d, code, 0, 0)
        self._flush()

    def drag(self, points, seconds):
        """Presses at the first point, moves through the others over `seconds`, releases."""
        self.move(*points[0])
        self.button(True)
        step = seconds / max(1, len(points) - 1)
        for p in points[1:]:
            time.sleep(step)
            self.move(*p)
        self.button(False)

    def pixels(self, x, y, w, h):
        """The screen's pixels in a rectangle, rows of (r, g, b) tuples."""
        image = _x11.XGetImage(self.d, self.root, x, y, w, h, 0xFFFFFFFF, 2)  # ZPixmap
        if not image:
            raise RuntimeError("XGetImage failed")
        img = ctypes.cast(image, ctypes.POINTER(_XImage)).contents
        stride, data = img.bytes_per_line, img.data
        rows = []
        for j in range(h):
            row = []
            base = j * stride
            for i in range(w):
                o = base + 4 * i
                row.append((data[o + 2], data[o + 1], data[o]))
            rows.append(row)
        return rows
