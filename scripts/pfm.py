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
