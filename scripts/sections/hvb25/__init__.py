"""hvb25 report sections: one module per study (hvb25_accuracy, hvb25_render);
each dispatches on the run's config name."""
TITLE = "Horváth, Valasek & Bán 2025 — distance fields from geometric proxies"
RANK = 30
