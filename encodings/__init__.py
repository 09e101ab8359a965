"""Reference encodings per domain and style, and the registry that finds them."""
