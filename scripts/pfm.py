"""PFM files (gpurt's AOVs) for the scripts, with the standard library only."""
import array


def read_pfm(path):
    """(width, height, channels, values): values bottom row first, as the file stores them."""
    with open(path, "rb") as f:
        kind = f.readline().strip()
        w, h = map(int, f.readline().split())
        scale = float(f.readline())
        values = array.array("f")
        values.frombytes(f.read())
    if scale > 0:
        values.byteswap()
    return w, h, (3 if kind == b"PF" else 1), values


def rel_mse(x, ref):
    """relMSE of values x against ref: the mean of (x - ref)^2 / (ref^2 + 0.01)."""
    return sum((a - b) ** 2 / (b * b + 0.01) for a, b in zip(x, ref)) / len(ref)
