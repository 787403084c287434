"""bs04 report sections: one module per study, named after it."""
TITLE = "Biswas & Shapiro 2004 — approximate distance fields by R-functions"
RANK = 10
