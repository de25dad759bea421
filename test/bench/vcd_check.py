#!/usr/bin/env python3
"""A small, strict VCD reader: parses a file the way a waveform viewer must
and returns its wires and value changes, or raises ValueError."""
import re
import sys


def read_vcd(path):
    text = open(path).read()
    header, sep, body = text.partition("$enddefinitions $end")
    if not sep:
        raise ValueError("no $enddefinitions")
    m = re.search(r"\$timescale\s+(\d+)\s*(s|ms|us|ns|ps|fs)\s+\$end", header)
    if not m:
        raise ValueError("no timescale")
    scale = int(m.group(1)) * {"s": 1e12, "ms": 1e9, "us": 1e6, "ns": 1e3, "ps": 1, "fs": 1e-3}[m.group(2)]
    scopes, wires, stack = [], {}, []
    for tok in re.finditer(r"\$(scope|upscope|var)\b(.*?)\$end", header, re.S):
        kind, args = tok.group(1), tok.group(2).split()
        if kind == "scope":
            stack.append(args[1])
            scopes.append(args[1])
        elif kind == "upscope":
            stack.pop()
        else:
            vtype, width, code, name = args[0], int(args[1]), args[2], args[3]
            if width != 1:
                raise ValueError("wire %s is not 1 bit" % name)
            wires[code] = ("/".join(stack), name)
    if stack:
        raise ValueError("unbalanced $scope")
    changes = {code: [] for code in wires}
    t, last_t = 0, -1
    for line in body.split():
        if line.startswith("$"):
            continue
        if line.startswith("#"):
            t = int(line[1:])
            if t < last_t:
                raise ValueError("time goes backwards at #%d" % t)
            last_t = t
        elif line[0] in "01xXzZ" and line[1:] in wires:
            changes[line[1:]].append((t * scale, line[0]))
        else:
            raise ValueError("bad line %r" % line)
    return scale, {wires[c]: v for c, v in changes.items()}


if __name__ == "__main__":
    scale, data = read_vcd(sys.argv[1])
    for (scope, name), ch in data.items():
        print(scope, name, len(ch))
