"""sjp10 report sections: one module per study, named after it."""
TITLE = "Song, Jüttler & Poteaux 2010 — PHT-spline approximation of the signed distance function"
RANK = 20
