"""The modular plan checker: logic programs per domain and the diagnostics built on them."""
