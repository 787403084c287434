"""Report sections of the studies that belong to no paper (smoke)."""
TITLE = "Smoke studies"
RANK = 90
