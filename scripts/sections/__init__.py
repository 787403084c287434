"""Report sections, one folder per paper (sections/<paper>/<study>.py).

A paper folder's __init__.py sets TITLE (the report heading) and RANK (its
place in the report, smaller first); report.py finds a study's section by
looking for a module named after the study in each folder."""
