"""memfile.py - little-endian words in a file standing in for /dev/mem
(the tests' stand-in board: bissctl --devmem FILE)."""


def rd(mem, at, n=4):
    """The n-byte word at offset at of the file mem."""
    with open(mem, "rb") as f:
        f.seek(at)
        return int.from_bytes(f.read(n), "little")


def wr(mem, at, v, n=4):
    """Writes v as an n-byte word at offset at of the file mem."""
    with open(mem, "r+b") as f:
        f.seek(at)
        f.write(v.to_bytes(n, "little"))
