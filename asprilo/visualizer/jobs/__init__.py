"""Work the window starts and keeps running: generate, solve and check in worker threads (the
Run menu), and the online link to a solver and a simulator (the Online menu)."""
