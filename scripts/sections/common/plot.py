"""Plotting helpers shared by the report sections of every paper."""


def pyplot():
    """matplotlib.pyplot on the Agg backend: report figures are files, never
    windows, and the report runs without a display."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt
