"""fdt.py - a flattened device tree (.dtb) read into nodes, and the pads the
enabled nodes claim through pinctrl-single.

The blob layout is the Devicetree Specification's (v0.4, chapter 5: header,
structure block of FDT_BEGIN_NODE / FDT_END_NODE / FDT_PROP / FDT_NOP /
FDT_END tokens, strings block). Written here rather than taken from
Debian's python3-libfdt because that binding (1.6.1, bookworm) aborts the
interpreter under Python 3.11 ("none_dealloc: deallocating None").

What counts as a claim follows Linux's pinctrl core: a device's pinctrl-N
properties name pin groups (phandles); for a pinctrl-single controller a
group's "pinctrl-single,pins" lists (offset, value[, ...]) with
1 + #pinctrl-cells words per pad (Documentation/devicetree/bindings/
pinctrl/pinctrl-single.yaml). A node takes part only when it and every
ancestor are enabled (status absent, "okay" or "ok": of_device_is_available
for the node, and a disabled bus populates no children). All states count,
not only "default": a bone-pinmux-helper switches between them at run time
(config-pin), and every state of one helper is the same pad.
"""
import struct

FDT_MAGIC = 0xD00DFEED
FDT_BEGIN_NODE, FDT_END_NODE, FDT_PROP, FDT_NOP, FDT_END = 1, 2, 3, 4, 9


class Node:
    def __init__(self, name, parent):
        self.name = name
        self.parent = parent
        self.props = {}
        self.children = []

    def path(self):
        if self.parent is None:
            return "/"
        up = self.parent.path()
        return (up if up != "/" else "") + "/" + self.name

    def cells(self, prop):
        """A property as big-endian 32-bit cells."""
        b = self.props[prop]
        return list(struct.unpack(">%dI" % (len(b) // 4), b))

    def string(self, prop):
        return self.props[prop].rstrip(b"\0").decode()

    def child(self, name):
        for c in self.children:
            if c.name == name:
                return c
        return None

    def walk(self):
        yield self
        for c in self.children:
            yield from c.walk()


def parse(blob):
    """The tree in a .dtb: its root Node."""
    (magic, _total, off_struct, off_strings, _rsv, _ver, _comp, _cpu, size_strings,
     _size_struct) = struct.unpack_from(">10I", blob, 0)
    if magic != FDT_MAGIC:
        raise ValueError("not a flattened device tree (magic 0x%08x)" % magic)
    strings = blob[off_strings:off_strings + size_strings]
    pos, root, cur = off_struct, None, None
    while True:
        (tok,) = struct.unpack_from(">I", blob, pos)
        pos += 4
        if tok == FDT_BEGIN_NODE:
            end = blob.index(b"\0", pos)
            node = Node(blob[pos:end].decode(), cur)
            pos = (end + 1 + 3) & ~3
            if cur is None:
                root = node
            else:
                cur.children.append(node)
            cur = node
        elif tok == FDT_END_NODE:
            cur = cur.parent
        elif tok == FDT_PROP:
            length, nameoff = struct.unpack_from(">II", blob, pos)
            pos += 8
            name = strings[nameoff:strings.index(b"\0", nameoff)].decode()
            cur.props[name] = blob[pos:pos + length]
            pos = (pos + length + 3) & ~3
        elif tok == FDT_NOP:
            pass
        elif tok == FDT_END:
            return root
        else:
            raise ValueError("bad structure token %d at offset %d" % (tok, pos - 4))


def read(path):
    with open(path, "rb") as f:
        return parse(f.read())


def find(root, path):
    """The node at an absolute path, or None."""
    node = root
    for part in [p for p in path.split("/") if p]:
        node = node.child(part)
        if node is None:
            return None
    return node


def enabled(node):
    """The node and all its ancestors available (status okay or absent)."""
    while node is not None:
        if "status" in node.props and node.string("status") not in ("okay", "ok"):
            return False
        node = node.parent
    return True


def pad_claims(root):
    """{(controller path, pad offset): set of claiming node paths} over every
    enabled node's pinctrl-N groups."""
    by_phandle = {}
    for n in root.walk():
        for key in ("phandle", "linux,phandle"):
            if key in n.props:
                by_phandle[n.cells(key)[0]] = n
    claims = {}
    for n in root.walk():
        if not enabled(n):
            continue
        state = 0
        while "pinctrl-%d" % state in n.props:
            for handle in n.cells("pinctrl-%d" % state):
                group = by_phandle.get(handle)
                if group is None:
                    raise ValueError("%s: pinctrl-%d names phandle 0x%x, which no node has"
                                     % (n.path(), state, handle))
                if "pinctrl-single,pins" not in group.props:
                    continue
                ctl = group.parent
                step = 1 + (ctl.cells("#pinctrl-cells")[0] if "#pinctrl-cells" in ctl.props
                            else 1)
                words = group.cells("pinctrl-single,pins")
                for i in range(0, len(words), step):
                    claims.setdefault((ctl.path(), words[i]), set()).add(n.path())
            state += 1
    return claims


def double_claims(root):
    """The pads two or more enabled nodes claim: {(controller, pad): claimants}."""
    return {k: v for k, v in pad_claims(root).items() if len(v) > 1}
