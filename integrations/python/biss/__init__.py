"""biss: the BiSS-C master on a PRU (libbiss) from Python.

    import biss
    with biss.open("emu") as m:           # or "am335x", "am437x-icss0", ...
        m.configure_from_emulator()       # the bench encoder's layout; on a
        m.start()                         # board: m.configure(slaves=[...])
        s = m.wait()
        print(s.frame, s.valid, s.positions)

Every call is libbiss's (host/include/libbiss.h says what each does); a
failure raises BissError with the library's error code, its name and its
text (and, for an open, the path, errno and hint libbiss wrote). The C
declarations come from libbiss's own headers (gen_cdef.py), read by cffi at
import; the library is found next to this file (the build tree's
libbiss-emu.so, which has the emulator), else by $BISS_LIBRARY, else as the
installed libbiss.so.0 (boards: no emulator target).
"""

import builtins
import os

import cffi

__all__ = ["BissError", "Master", "Sample", "Slave", "open", "strerror"]

_here = os.path.dirname(os.path.abspath(__file__))
ffi = cffi.FFI()
with builtins.open(os.path.join(_here, "_cdef.h")) as _f:  # (open is biss.open below)
    ffi.cdef(_f.read())


def _find_library():
    env = os.environ.get("BISS_LIBRARY")
    if env:
        return env
    local = os.path.join(_here, "libbiss-emu.so")
    if os.path.exists(local):
        return local
    return "libbiss.so.0"


lib = ffi.dlopen(_find_library())
try:  # the build tree's module: the build tree's images (CMakeLists.txt)
    from ._build import FIRMWARE as _BUILD_FIRMWARE
except ImportError:
    _BUILD_FIRMWARE = None
HAS_EMULATOR = hasattr(lib, "biss_emu_open")

_ERRNAMES = {getattr(lib, n): n for n in dir(lib) if n.startswith("BISS_E_")}


class BissError(Exception):
    """A libbiss error: code (BISS_E_*, negative), name and text; detail is
    what the library wrote into the open's error buffer, if anything."""

    def __init__(self, code, what, detail=""):
        self.code = code
        self.name = _ERRNAMES.get(code, str(code))
        self.text = strerror(code)
        self.detail = detail
        msg = "%s: %s (%s)" % (what, self.text, self.name)
        if detail:
            msg += ": " + detail
        super().__init__(msg)


def strerror(code):
    """libbiss's text for an error code."""
    return ffi.string(lib.biss_strerror(code)).decode()


def _check(rc, what, detail=""):
    if rc < 0:
        raise BissError(rc, what, detail)
    return rc


class Slave:
    """One slave's layout (struct biss_slave_config): data_bits (1..64),
    crc_bits (0..16), crc_poly (with its top term: 0x43), crc_start,
    has_ew, ew_shift, pos_bits (0: all above nE/nW), and the safety checks
    life_check, life_bits, ew_static, max_speed."""

    FIELDS = ("data_bits", "crc_bits", "crc_poly", "crc_start", "has_ew", "ew_shift", "pos_bits",
              "ssi", "gray", "life_check", "life_bits", "ew_static", "max_speed")

    def __init__(self, data_bits, crc_bits=6, crc_poly=0x43, **kw):
        self.data_bits, self.crc_bits, self.crc_poly = data_bits, crc_bits, crc_poly
        unknown = set(kw) - set(self.FIELDS)
        if unknown:
            raise TypeError("Slave: unknown field(s) %s" % ", ".join(sorted(unknown)))
        for k, v in kw.items():
            setattr(self, k, v)

    def _fill(self, c):
        for k in self.FIELDS:
            if hasattr(self, k):
                setattr(c, k, getattr(self, k))

    @classmethod
    def _from(cls, c):
        s = cls(c.data_bits)
        for k in cls.FIELDS:
            setattr(s, k, getattr(c, k))
        return s

    def __repr__(self):
        return "Slave(%s)" % ", ".join("%s=%r" % (k, getattr(self, k))
                                      for k in self.FIELDS if hasattr(self, k))


class Sample:
    """One published frame (struct biss_sample): frame, seq, flags, valid,
    crc_error, no_slave, proc_error, training, ack_jump, off_grid (an SL
    edge off the bit grid, below 10 MHz), misframed, timestamp (IEP
    count of the first MA edge), proc_clocks, cds, sample_point,
    lag_periods, line_delay_ns; per slave positions, data, crc_ok, errors
    (nE), warnings (nW)."""

    SCALARS = ("seq", "frame", "flags", "valid", "crc_error", "no_slave", "proc_error", "training",
               "sma", "ack_jump", "off_grid", "misframed", "timestamp", "proc_clocks", "cds",
               "sample_point", "lag_periods", "nslaves", "safety", "link_eye", "link_warning")

    def __init__(self, s):
        for k in self.SCALARS:
            setattr(self, k, getattr(s, k))
        n = s.nslaves
        self.line_delay_ns = s.delay.ns
        self.positions = [s.slave[i].position for i in range(n)]
        self.data = [s.slave[i].data for i in range(n)]
        self.crc_ok = [bool(s.slave[i].crc_ok) for i in range(n)]
        self.errors = [bool(s.slave[i].error) for i in range(n)]
        self.warnings = [bool(s.slave[i].warning) for i in range(n)]

    def __repr__(self):
        return "Sample(frame=%d, valid=%s, positions=%s)" % (self.frame, self.valid, self.positions)


_TARGETS = {"emu": "BISS_TARGET_EMU"}


def open(target="emu", *, pru=0, profile=None, scenario=None, cable_m=None, seed=None,
         firmware=None, devmem=None, attach=False, loader=None, timeout_ms=0):
    """Opens a master (biss_open): target "emu" (the emulator: profile or
    scenario file, cable length, seed) or a board ("am335x",
    "am437x-icss0", "am437x-icss1": firmware image, devmem, attach to a
    running master, loader "remoteproc" or "devmem"). Returns a Master."""
    return Master(target, pru=pru, profile=profile, scenario=scenario, cable_m=cable_m, seed=seed,
                  firmware=firmware, devmem=devmem, attach=attach, loader=loader,
                  timeout_ms=timeout_ms)


class Master:
    """A handle on one PRU's BiSS-C master (biss_t). Use as a context
    manager, or call close()."""

    def __init__(self, target, **o):
        p = ffi.new("struct biss_open_params *")
        lib.biss_open_params_default(p)
        t = ffi.new("enum biss_target *")
        _check(lib.biss_target_from_name(target.encode(), t), "target %r" % target)
        p.target = t[0]
        keep = []  # the strings p points to live as long as the call

        def cstr(v):
            b = ffi.new("char[]", os.fsencode(v))
            keep.append(b)
            return b

        if o["loader"] is not None:
            lo = ffi.new("enum biss_loader *")
            _check(lib.biss_loader_from_name(o["loader"].encode(), lo), "loader %r" % o["loader"])
            p.loader = lo[0]
        if o["firmware"] is None and not os.environ.get("BISS_FIRMWARE") and _BUILD_FIRMWARE:
            o["firmware"] = _BUILD_FIRMWARE[1 if o["pru"] else 0]
        for field, key in (("profile", "profile"), ("scenario_file", "scenario"),
                           ("firmware", "firmware"), ("devmem", "devmem")):
            if o[key] is not None:
                setattr(p, field, cstr(o[key]))
        if o["cable_m"] is not None:
            p.cable_m = o["cable_m"]
        if o["seed"] is not None:
            p.set_seed, p.seed = True, o["seed"]
        p.attach, p.pru, p.timeout_ms = o["attach"], o["pru"], o["timeout_ms"]
        err = ffi.new("char[512]")
        p.errbuf, p.errbuf_len = err, 512
        h = ffi.new("biss_t **")
        if p.target == lib.BISS_TARGET_EMU:
            if not HAS_EMULATOR:
                raise BissError(lib.BISS_E_TARGET, "open emu",
                                "this libbiss has no emulator (build tree's libbiss-emu.so)")
            rc = lib.biss_emu_open(p, h)
        else:
            rc = lib.biss_open(p, h)
        _check(rc, "open %s" % target, ffi.string(err).decode(errors="replace"))
        self._h = h[0]
        self.target = target

    def _handle(self):
        if self._h is None:
            raise ValueError("the master is closed")
        return self._h

    def close(self):
        """biss_close (the firmware stops, unless leave_running was called)."""
        if self._h is not None:
            lib.biss_close(self._h)
            self._h = None

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def __del__(self):
        try:
            self.close()
        except Exception:
            pass

    # ---- configuration and running -------------------------------------
    def configure(self, slaves, freq_hz=None, trigger=None, iep_period_ns=None, proc_limit=None):
        """biss_configure: the slaves (Slave objects, nearest the master
        first) and the MA rate, trigger ("freerun", "host", "iep",
        "iep-follow"), IEP period and processing-time limit; what is not
        given keeps libbiss's default (biss_config_default)."""
        c = ffi.new("struct biss_config *")
        lib.biss_config_default(c)
        if not 1 <= len(slaves) <= lib.BISS_API_MAX_SLAVES:
            raise BissError(lib.BISS_E_NSLAVES, "configure")
        c.nslaves = len(slaves)
        for i, s in enumerate(slaves):
            s._fill(c.slave[i])
        if freq_hz is not None:
            c.freq_hz = freq_hz
        if trigger is not None:
            t = ffi.new("enum biss_trigger *")
            _check(lib.biss_trigger_from_name(trigger.encode(), t), "trigger %r" % trigger)
            c.trigger = t[0]
        if iep_period_ns is not None:
            c.iep_period_ns = iep_period_ns
        if proc_limit is not None:
            c.proc_limit = proc_limit
        _check(lib.biss_configure(self._handle(), c), "configure")

    def configure_from_emulator(self, **kw):
        """configure() with the bench encoder's own layout
        (biss_config_from_emu); keywords as configure()'s."""
        c = ffi.new("struct biss_config *")
        lib.biss_config_default(c)
        _check(lib.biss_config_from_emu(self._handle(), c), "layout of the emulated encoder")
        self.configure([Slave._from(c.slave[i]) for i in range(c.nslaves)], **kw)

    def config(self):
        """biss_get_config: (freq_hz, trigger name, [Slave, ...])."""
        c = ffi.new("struct biss_config *")
        _check(lib.biss_get_config(self._handle(), c), "get_config")
        return (c.freq_hz, ffi.string(lib.biss_trigger_name(c.trigger)).decode(),
                [Slave._from(c.slave[i]) for i in range(c.nslaves)])

    def start(self):
        _check(lib.biss_start(self._handle()), "start")

    def stop(self):
        _check(lib.biss_stop(self._handle()), "stop")

    def trigger(self):
        """One frame (host trigger)."""
        _check(lib.biss_trigger(self._handle()), "trigger")

    def run_ms(self, ms):
        """Lets time pass: the emulator runs ms simulated milliseconds."""
        _check(lib.biss_run_ms(self._handle(), ms), "run_ms")

    def run_us(self, us):
        """The same in microseconds (a ring reader polling more often than
        once a millisecond)."""
        _check(lib.biss_run_us(self._handle(), us), "run_us")

    # ---- samples ----------------------------------------------------------
    def _latest_frame(self, s):
        """The newest published frame's number (into s), or the number
        before frame 0 when none is published yet: what to wait after."""
        return s.frame if lib.biss_read_sample(self._handle(), s) == 0 else 0xFFFFFFFF

    def read(self):
        """The latest published frame (biss_read_sample)."""
        s = ffi.new("struct biss_sample *")
        _check(lib.biss_read_sample(self._handle(), s), "read")
        return Sample(s)

    def wait(self, after_frame=None, timeout_ms=100):
        """The first frame published after after_frame (default: the
        latest one now, or any if none yet) (biss_wait_sample)."""
        s = ffi.new("struct biss_sample *")
        if after_frame is None:
            after_frame = self._latest_frame(s)
        _check(lib.biss_wait_sample(self._handle(), after_frame & 0xFFFFFFFF, timeout_ms, s), "wait")
        return Sample(s)

    def read_batch(self, n, timeout_ms=100):
        """The next n published frames, each waited for in turn, as numpy
        arrays: frame, valid, crc_error, off_grid, link_eye, timestamp (n)
        and position (n x slaves). Frames the firmware published between two of them (a
        slow host on a board) are not in it: compare `frame`."""
        import numpy as np

        s = ffi.new("struct biss_sample *")
        h = self._handle()
        last = self._latest_frame(s)
        out = {"frame": np.zeros(n, np.uint32), "valid": np.zeros(n, bool),
               "crc_error": np.zeros(n, bool), "off_grid": np.zeros(n, bool),
               "link_eye": np.zeros(n, np.int8), "timestamp": np.zeros(n, np.uint32)}
        pos = None
        for i in range(n):
            _check(lib.biss_wait_sample(h, last, timeout_ms, s), "read_batch")
            if pos is None:
                pos = np.zeros((n, s.nslaves), np.uint64)
            last = s.frame
            out["frame"][i], out["valid"][i] = s.frame, s.valid
            out["crc_error"][i], out["timestamp"][i] = s.crc_error, s.timestamp
            out["off_grid"][i], out["link_eye"][i] = s.off_grid, s.link_eye
            for k in range(min(s.nslaves, pos.shape[1])):
                pos[i, k] = s.slave[k].position
        out["position"] = pos if pos is not None else np.zeros((0, 0), np.uint64)
        return out

    def read_ring(self, max_frames=1024):
        """Every frame published since the last call, oldest first, at
        most max_frames (the rest wait for the next call), from the
        firmware's result ring (biss_ring_read): (samples, lost), lost the
        frames the ring no longer held (the host read too rarely). Each
        Sample's seq is its publication number."""
        buf = ffi.new("struct biss_sample[]", max_frames)
        n = ffi.new("unsigned *")
        lost = ffi.new("uint32_t *")
        _check(lib.biss_ring_read(self._handle(), buf, max_frames, n, lost), "read_ring")
        return [Sample(buf[i]) for i in range(n[0])], lost[0]

    def ring_capacity(self):
        """Frames the ring keeps for a reader at this configuration
        (biss_ring_capacity): read it at least that often."""
        n = ffi.new("unsigned *")
        _check(lib.biss_ring_capacity(self._handle(), n), "ring_capacity")
        return n[0]

    def line_delay_ns(self):
        """The measured round trip, averaged (biss_line_delay)."""
        d = ffi.new("struct biss_line_delay *")
        _check(lib.biss_line_delay(self._handle(), d), "line_delay")
        return d.ns

    def status(self):
        """biss_get_status as a dict (state named)."""
        st = ffi.new("struct biss_status *")
        _check(lib.biss_get_status(self._handle(), st), "status")
        d = {k: getattr(st, k) for k in ("firmware_running", "pru_enabled", "state", "cfg_seq",
                                         "cfg_ack", "cfg_error", "seq", "shm_version", "image_crc")}
        d["state_name"] = ffi.string(lib.biss_fw_state_name(st.state)).decode()
        return d

    def link_stats(self):
        """biss_get_link_stats as a dict over the frames this handle read:
        frames, eye (counts by eye opening 0..4 eighths of a bit), eye_mean,
        eye_min, marginal, off_grid, last_block_marginal, warnings."""
        st = ffi.new("struct biss_link_stats *")
        _check(lib.biss_get_link_stats(self._handle(), st), "link_stats")
        d = {k: getattr(st, k) for k in ("frames", "eye_min", "marginal", "off_grid",
                                         "last_block_marginal", "warnings")}
        d["eye"] = list(st.eye)
        d["eye_mean"] = st.eye_sum / st.frames if st.frames else float(d["eye_min"])
        return d

    def set_link_warning(self, window, warn):
        """biss_set_link_warning: warn after `warn` marginal frames in a
        block of `window` frames read."""
        _check(lib.biss_set_link_warning(self._handle(), window, warn), "set_link_warning")

    def stats(self):
        """biss_get_stats as a dict: frames, crc_errors, no_slave,
        proc_errors, training, off_grid."""
        st = ffi.new("struct biss_stats *")
        _check(lib.biss_get_stats(self._handle(), st), "stats")
        return {k: getattr(st, k) for k in ("frames", "crc_errors", "no_slave", "proc_errors",
                                            "training", "off_grid")}

    # ---- discovery ------------------------------------------------------------
    def probe(self, freq_hz=1000000, frames=0, read_regs=True):
        """biss_probe: an unknown encoder's layout from raw frames (and its
        identification registers). Returns a dict: verdict (unique, best,
        ambiguous, ...), reason, frames, delay_ns, layouts (each as its
        biss-sim scenario, a dict, with a configure()-ready "slaves" list),
        notes. The master's configuration afterwards is the probe's."""
        import json

        p = ffi.new("struct biss_probe_params *")
        p.freq_hz, p.frames, p.read_regs = freq_hz, frames, read_regs
        r = ffi.new("struct biss_probe_report *")
        _check(lib.biss_probe(self._handle(), p, r), "probe")
        w = r.wire
        layouts = []
        buf = ffi.new("char[8192]")
        for i in range(w.nkept):
            _check(lib.biss_probe_to_json(ffi.addressof(w.layout[i]), buf, 8192), "probe layout")
            c = ffi.new("struct biss_config *")
            lib.biss_config_default(c)
            lib.biss_probe_layout_config(ffi.addressof(w.layout[i]), c)
            d = json.loads(ffi.string(buf).decode())
            d["slaves"] = [Slave._from(c.slave[k]) for k in range(c.nslaves)]
            layouts.append(d)
        return {"verdict": ffi.string(lib.biss_probe_verdict_name(w.verdict)).decode(),
                "reason": ffi.string(w.reason).decode(), "frames": w.frames,
                "delay_ns": r.delay_ns, "layouts": layouts,
                "notes": [ffi.string(r.notes[i]).decode() for i in range(r.nnotes)]}

    # ---- control communication --------------------------------------------
    def reg_read(self, slave_id, addr, n=1):
        """n bytes from slave_id's registers from addr (biss_reg_read)."""
        buf = ffi.new("uint8_t[]", max(n, 1))
        _check(lib.biss_reg_read(self._handle(), slave_id, addr, buf, n), "reg_read")
        return bytes(ffi.buffer(buf, n))

    def reg_write(self, slave_id, addr, data):
        """data to slave_id's registers from addr (biss_reg_write)."""
        data = bytes(data)
        _check(lib.biss_reg_write(self._handle(), slave_id, addr, data, len(data)), "reg_write")

    def command(self, ids, cmd, check_ida=True):
        """A BiSS command to the slaves in the ids mask (biss_command);
        returns the IDA bits read back."""
        ida = ffi.new("uint8_t *")
        _check(lib.biss_command(self._handle(), ids, cmd, check_ida, ida), "command")
        return ida[0]
