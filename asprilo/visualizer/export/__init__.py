"""Pictures and animations: the files written (PNG, JPEG, SVG, GIF, MP4), ``render()`` without
a window, and File > Export in the window."""
