"""The layout editor: the Edit menu and its commands, the palette of edit tools, the mouse
while editing, the order editor."""
