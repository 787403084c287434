"""The comparison study's report section (experiments/compare/): every
dflab method side by side on the same shapes under one protocol."""
TITLE = "All methods side by side"
RANK = 40
