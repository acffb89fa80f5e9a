"""The Tippe-Top against the peer engines (scripts/dev/compare, scripts/dev/compare_report.py), in three
parts: run (the plan and the pinned, interleaved runs, and their log), analyse (medians, costs,
ratios) and report (the page and its figure)."""
