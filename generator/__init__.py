"""The instance generator: logic programs per scenario dimension and their multi-shot driver."""
