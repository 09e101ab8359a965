"""Benchmarking: YAML suites, a runner with OS-enforced limits, reports like the paper's, cluster export."""
