# The one colour scale of the scaled Jacobian, shared by the task panel's histogram and the
# Mesh quality view, so that a band has the same colour in both. Colour-blind safe (Okabe &
# Ito's colours, wine for inverted): colour_check.py measures every pair apart by at least
# 11 CIEDE2000 units for normal vision and each dichromacy (tests/python checks it).


def rgb(hex_colour):
    """'#0072B2' -> (r, g, b) in 0..1."""
    return tuple(int(hex_colour[i:i + 2], 16) / 255.0 for i in (1, 3, 5))


# Bands, worst first: (upper bound, colour, label). A value belongs to the first band
# whose upper bound it does not exceed (so 0 is inverted, 0.2 poor).
BANDS = (
    (0.0, rgb("#882255"), "inverted (<= 0)"),
    (0.2, rgb("#D55E00"), "0 - 0.2 (poor)"),
    (0.4, rgb("#E69F00"), "0.2 - 0.4"),
    (0.6, rgb("#F0E442"), "0.4 - 0.6"),
    (0.8, rgb("#56B4E9"), "0.6 - 0.8"),
    (1.01, rgb("#0072B2"), "0.8 - 1 (good)"),
)


def band(value):
    """Index into BANDS of a scaled Jacobian."""
    for i, (upper, _, _) in enumerate(BANDS):
        if value <= upper:
            return i
    return len(BANDS) - 1


def band_colour(value):
    return BANDS[band(value)][1]
