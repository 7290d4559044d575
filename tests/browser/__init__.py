"""Browser tests of the calculator page (headless chromium against a real uvicorn)."""
