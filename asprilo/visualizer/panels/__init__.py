"""The window's widgets beside the map: the side panels (tables of orders, inventory, robots,
plan and violations in docks; the atoms pane; the legend), the transport and status bars, the
session banner, the dialogs, the File menu and the menu commands built from tables."""
