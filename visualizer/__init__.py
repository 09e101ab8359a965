"""The Qt visualizer and layout editor."""
