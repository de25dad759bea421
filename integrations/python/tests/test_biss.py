"""The module `biss` against the emulator target: the real firmware image
on the emulated PRU, read through libbiss (libbiss-emu.so) from Python."""

import os

import numpy as np
import pytest

import biss

SCENARIOS = os.path.join(os.path.dirname(__file__), "..", "..", "..", "test", "scenarios")


@pytest.fixture
def master():
    with biss.open("emu", cable_m=10, seed=1) as m:
        m.configure_from_emulator(freq_hz=5000000)
        m.start()
        s = m.wait()
        while s.training:  # the first frames measure the line
            s = m.wait(after_frame=s.frame)
        yield m


def test_positions_advance_as_the_encoder_turns(master):
    b = master.read_batch(200)
    assert b["valid"].all() and not b["crc_error"].any()
    # consecutive frames (the emulator lets no frame pass unread)
    assert (np.diff(b["frame"].astype(np.int64)) == 1).all()
    steps = np.diff(b["position"][:, 0].astype(np.int64)) % 4096  # its 12-bit position
    # the default encoder turns at a constant speed, sampled once a frame
    # period: every step k or k + 1 counts, and it moves
    assert steps.max() - steps.min() <= 1 and steps.sum() > 0
    assert b["position"].shape == (200, 1)


def test_every_frame_from_the_ring(master):
    # at 5 MHz a frame takes some 25 us: 40 a ms, the ring keeps 59
    assert master.ring_capacity() == 59
    master.read_ring()  # from here on
    seqs, lost = [], 0
    for _ in range(20):
        master.run_ms(1)
        got, gone = master.read_ring()
        seqs += [x.seq for x in got]
        lost += gone
        assert all(x.valid and x.frame == x.seq for x in got)
    assert lost == 0 and len(seqs) > 700
    assert seqs == list(range(seqs[0], seqs[0] + len(seqs)))
    master.run_ms(3)  # too long: the ring keeps the newest 59
    got, gone = master.read_ring()
    assert len(got) == 59 and gone > 0 and got[0].seq == seqs[-1] + gone + 1
    # polled every 250 us: some 10 frames a call, none lost
    master.read_ring()
    seqs = []
    for _ in range(40):
        master.run_us(250)
        got, gone = master.read_ring()
        assert gone == 0 and 5 <= len(got) <= 15
        seqs += [x.seq for x in got]
    assert seqs == list(range(seqs[0], seqs[0] + len(seqs)))


def test_a_sample_carries_the_frame(master):
    s = master.wait()
    assert s.valid and s.nslaves == 1 and s.crc_ok == [True]
    assert not s.errors[0] and not s.warnings[0]
    assert s.line_delay_ns > 0 and 0 <= s.sample_point < 8
    t = master.wait(after_frame=s.frame)
    assert t.frame == s.frame + 1


def test_stats_and_status_count_the_frames(master):
    a = master.stats()["frames"]
    master.run_ms(2)
    b = master.stats()
    assert b["frames"] > a and b["crc_errors"] == 0
    st = master.status()
    assert st["firmware_running"] and st["state_name"] == "running"


def test_configuration_read_back(master):
    freq, trigger, slaves = master.config()
    assert freq == 5000000 and trigger == "free"
    assert slaves[0].data_bits == 14 and slaves[0].crc_poly == 0x43


def test_registers_written_and_read_back(master):
    master.reg_write(0, 0x10, b"\x12\x34\x56")
    assert master.reg_read(0, 0x10, 3) == b"\x12\x34\x56"


def test_a_refused_configuration_raises_with_code_and_text(master):
    with pytest.raises(biss.BissError) as e:
        master.configure([biss.Slave(70)])
    assert e.value.code == biss.lib.BISS_E_DATA_BITS and e.value.name == "BISS_E_DATA_BITS"
    assert "data bits" in e.value.text and "BISS_E_DATA_BITS" in str(e.value)
    with pytest.raises(biss.BissError) as e:
        master.configure([biss.Slave(14)], freq_hz=3000000)  # 100 MHz / 3 MHz: no whole H
    assert e.value.code == biss.lib.BISS_E_RATE_INEXACT


def test_a_board_open_names_the_path_and_errno():
    with pytest.raises(biss.BissError) as e:
        biss.open("am335x", loader="devmem", devmem="/nonexistent/mem")
    assert e.value.code == biss.lib.BISS_E_DEVMEM
    assert "/nonexistent/mem" in e.value.detail and "errno 2" in e.value.detail


def test_unknown_names_are_refused():
    with pytest.raises(biss.BissError) as e:
        biss.open("am999")
    assert e.value.code == biss.lib.BISS_E_TARGET
    with pytest.raises(biss.BissError) as e:
        biss.open("emu", profile="no-such-encoder")
    assert e.value.code == biss.lib.BISS_E_PROFILE


def test_a_fault_in_the_scenario_shows_in_the_samples():
    # both lines glitched: CRC errors, counted and flagged, never valid
    with biss.open("emu", scenario=os.path.join(SCENARIOS, "noise-both-30khz-jitter.json"),
                   seed=7) as m:
        m.configure_from_emulator(freq_hz=5000000)
        m.start()
        b = m.read_batch(3000)
        assert 0 < int(b["crc_error"].sum()) <= m.stats()["crc_errors"]
        assert b["valid"].sum() > 2000  # most frames still read
        # edges off the bit grid: refused (off_grid, never valid), counted by the
        # firmware, and the link's figure and warning show them
        assert int((b["off_grid"] & b["valid"]).sum()) == 0
        assert 0 < int(b["off_grid"].sum()) <= m.stats()["off_grid"]
        k = m.link_stats()
        assert k["marginal"] >= int(b["off_grid"].sum()) and k["warnings"] > 0
        assert k["eye_min"] <= 2 and sum(k["eye"]) == k["frames"]


def test_a_clean_line_shows_a_full_eye(master):
    master.read_batch(500)
    k = master.link_stats()
    assert k["frames"] >= 500 and k["marginal"] == 0 and k["warnings"] == 0
    assert k["eye_min"] >= 3 and master.stats()["off_grid"] == 0


def test_closed_master_refuses_calls():
    m = biss.open("emu")
    m.close()
    with pytest.raises(ValueError):
        m.read()
    m.close()  # twice is harmless


def test_probe_finds_the_encoders_layout():
    with biss.open("emu", profile="posital-kit-layout-biss-c", seed=3) as m:
        r = m.probe(frames=256)
        assert r["verdict"] == "unique", r["reason"]
        want = biss.open("emu", profile="posital-kit-layout-biss-c")
        try:
            want.configure_from_emulator()
            _, _, slaves = want.config()
        finally:
            want.close()
        got = r["layouts"][0]["slaves"]
        assert [(s.data_bits, s.crc_bits, s.crc_poly, s.has_ew) for s in got] == \
               [(s.data_bits, s.crc_bits, s.crc_poly, s.has_ew) for s in slaves]
        # the layout found configures the master, and it reads
        m.configure(got)
        m.start()
        s = m.wait()
        while s.training:
            s = m.wait(after_frame=s.frame)
        assert s.valid and s.crc_ok == [True]


def test_a_command_is_sent_and_its_ida_read():
    with biss.open("emu") as m:
        m.configure_from_emulator()
        m.start()
        m.run_ms(1)
        # command 0 addressed: "the data channel of each addressed slave on"
        # (harmless; proto/biss_cd_cmd.c)
        ida = m.command(0x01, 0, check_ida=True)
        assert ida & 0x01
