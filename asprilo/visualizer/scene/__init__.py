"""The warehouse picture: the QGraphics scene and its items and marks, the look (style,
drawing), the animation (animator, player clock), the view, and the stage that ties them
to the state."""
