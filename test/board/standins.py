"""standins.py - stand-ins for the base device trees the board overlays are
applied to, and for the overlays U-Boot applies after them. Each carries
what the pad check needs from the real tree: the labels the overlays name,
the real node names and paths, the pinctrl-single controller, every node
that claims one of our pads (the universal cape's bone-pinmux-helper
nodes, the HDMI framer, McASP0) with its pin groups and status, and the
status of the PRU-ICSS and its parents. Nothing else of the real trees is
carried.

Sources (read, not copied; each table below names its file):

  BBDT  github.com/beagleboard/BeagleBoard-DeviceTrees
        v4.19.x-ti          af07ef77cc6f8f94568a4c238cc6d41fb8c81931
        v4.19.x-ti-overlays a111bfeaba7eee6cdd62a9d6029e86226e71ced1
        v5.10.x-ti          707c9ac469b8a9eacb0f4f6dc0db10405f3becaf
        v6.1.x-ti           55d7cdc4d6aa77211033ae2fdb8b0c7217ba3939
  LINUX github.com/torvalds/linux (AM437x IDK, mainline)
        arch/arm/boot/dts/ti/omap/am4372.dtsi       0c8ea05e9b3d8e5287e2a968f2a2e744dfd31b99
        arch/arm/boot/dts/ti/omap/am437x-l4.dtsi    1260ed77798502de9c98020040d2995008de10cc
        arch/arm/boot/dts/ti/omap/am437x-idk-evm.dts 254a142007114cad7b0a901215c1558e4315d46f
  BBLINUX github.com/beagleboard/linux (TI 4.19 kernel tree)
        arch/arm/boot/dts/am437x-idk-evm.dts        10af54798c1d463663d5af6148fa510d6668e784

Node paths were read from the real trees compiled with dtc (their
__symbols__). Pad values in the stand-in groups keep the real mux modes;
the check reads only the offsets.
"""

# ---- a device tree as text --------------------------------------------------


class Tree:
    """Nodes by path; intermediate nodes are made on the way."""

    def __init__(self, plugin=False):
        self.plugin = plugin
        self.nodes = {}  # path -> [label, [props], [child paths]]
        self.order = []

    def node(self, path, label=None, *props):
        if path not in self.nodes:
            if not self._top(path):
                parent = path.rsplit("/", 1)[0] or "/"
                self.node(parent)
                self.nodes[parent][2].append(path)
            self.nodes[path] = [None, [], []]
            self.order.append(path)
        entry = self.nodes[path]
        if label:
            entry[0] = label
        entry[1].extend(props)
        return self

    @staticmethod
    def _top(path):
        """The root, or a reference to a labelled node (&label)."""
        return path == "/" or (path.startswith("&") and "/" not in path)

    def _emit(self, path, indent, out):
        label, props, children = self.nodes[path]
        name = path if self._top(path) else path.rsplit("/", 1)[1]
        tab = "\t" * indent
        out.append("%s%s%s {" % (tab, label + ": " if label else "", name))
        out.extend("%s\t%s;" % (tab, p) for p in props)
        for c in children:
            self._emit(c, indent + 1, out)
        out.append("%s};" % tab)

    def dts(self):
        out = ["/dts-v1/;"] + (["/plugin/;"] if self.plugin else [])
        for path in self.order:
            if self._top(path):
                self._emit(path, 0, out)
        return "\n".join(out) + "\n"


def group(tree, ctl, label, name, pads):
    """A pinctrl-single group under controller path ctl: pads is a list of
    (offset, value)."""
    cells = " ".join("0x%x 0x%x" % pv for pv in pads)
    tree.node("%s/%s" % (ctl, name), label, "pinctrl-single,pins = <%s>" % cells)


def controller(tree, path, label):
    tree.node(path, label, 'compatible = "pinctrl-single"', "#pinctrl-cells = <1>",
              "#address-cells = <1>", "#size-cells = <0>")


# ---- AM335x (BeagleBone Black, PocketBeagle) ---------------------------------

# label -> path per tree family. "ti": v5.10.x-ti and v6.1.x-ti
# (src/arm/am33xx.dtsi + am33xx-l4.dtsi: the same paths in both);
# "4.19": v4.19.x-ti (src/arm/am33xx.dtsi).
L4_WKUP_SCM = "/ocp/interconnect@44c00000/segment@200000/target-module@10000/scm@0"
AM335X = {
    "ti": dict(
        am33xx_pinmux=L4_WKUP_SCM + "/pinmux@800",
        i2c0="/ocp/interconnect@44c00000/segment@200000/target-module@b000/i2c@0",
        mcasp0="/ocp/interconnect@48000000/segment@0/target-module@38000/mcasp@0",
        lcdc="/ocp/interconnect@48000000/segment@300000/target-module@e000/lcdc@0",
        pruss_tm="/ocp/interconnect@4a000000/segment@0/target-module@300000",
        pruss="/ocp/interconnect@4a000000/segment@0/target-module@300000/pruss@0",
        pru0="/ocp/interconnect@4a000000/segment@0/target-module@300000/pruss@0/pru@34000",
        pru1="/ocp/interconnect@4a000000/segment@0/target-module@300000/pruss@0/pru@38000"),
    "4.19": dict(
        am33xx_pinmux="/ocp/l4_wkup@44c00000/scm@210000/pinmux@800",
        i2c0="/ocp/i2c@44e0b000",
        mcasp0="/ocp/mcasp@48038000",
        lcdc="/ocp/lcdc@4830e000",
        pruss_soc_bus="/ocp/pruss-soc-bus@4a326004",
        pruss="/ocp/pruss-soc-bus@4a326004/pruss@4a300000",
        pru0="/ocp/pruss-soc-bus@4a326004/pruss@4a300000/pru@4a334000",
        pru1="/ocp/pruss-soc-bus@4a326004/pruss@4a300000/pru@4a338000"),
}

# Status in the base trees (absent = enabled). ti: am33xx-l4.dtsi has
# pruss_tm "okay" (am335x-bone-common.dtsi sets it again), pruss@0 none;
# mcasp0 and lcdc "disabled" (the -uboot bases carry no HDMI). 4.19:
# am33xx.dtsi has pruss_soc_bus and pruss "disabled" until
# AM335X-PRU-RPROC-4-19-TI-00A0 enables them.
STATUS = {
    "ti": dict(pruss_tm="okay", mcasp0="disabled", lcdc="disabled", i2c0="okay"),
    "4.19": dict(pruss_soc_bus="disabled", pruss="disabled", mcasp0="disabled",
                 lcdc="disabled", i2c0="okay"),
}

# The bone-pinmux-helper nodes on our pads: name, pinctrl offset, default
# mode, and their pinctrl-names. BeagleBone Black: src/arm/
# am335x-bone-common-univ.dtsi (&ocp/P9_29_pinmux ...); PocketBeagle:
# src/arm/am335x-pocketbeagle.dts. v4.19.x-ti adds "gpio_input" after
# "gpio_pd". Modes per state: gpio* 7, spi* 3, pwm 1, pruout 5, pruin 6.
HELPERS = {
    "P9_29": (0x194, 7, ["default", "gpio", "gpio_pu", "gpio_pd", "spi", "pwm", "pruout",
                         "pruin"]),
    "P9_31": (0x190, 7, ["default", "gpio", "gpio_pu", "gpio_pd", "spi_sclk", "pwm", "pruout",
                         "pruin"]),
    "P8_45": (0x0a0, 7, ["default", "gpio", "gpio_pu", "gpio_pd", "pwm", "pruout", "pruin"]),
    "P8_46": (0x0a4, 7, ["default", "gpio", "gpio_pu", "gpio_pd", "pwm", "pruout", "pruin"]),
    "P1_33": (0x194, 6, ["default", "gpio", "gpio_pu", "gpio_pd", "spi", "pwm", "pruout",
                         "pruin"]),
    "P1_36": (0x190, 1, ["default", "gpio", "gpio_pu", "gpio_pd", "spi_sclk", "pwm", "pruout",
                         "pruin"]),
}
MODE = dict(gpio=7, gpio_pu=7, gpio_pd=7, gpio_input=7, spi=3, spi_sclk=3, pwm=1, pruout=5,
            pruin=6)
BBB_PINS = ["P9_29", "P9_31", "P8_45", "P8_46"]
PB_PINS = ["P1_33", "P1_36"]


def am335x_base(family, helpers):
    """The SoC's nodes as the family has them, and the named helpers."""
    t = Tree()
    paths, status = AM335X[family], STATUS[family]
    t.node("/chosen")
    t.node("/ocp", "ocp", "#address-cells = <1>", "#size-cells = <1>")
    for label, path in paths.items():
        if label == "am33xx_pinmux":
            controller(t, path, label)
        else:
            t.node(path, label)
        if label in status:
            t.node(path, None, 'status = "%s"' % status[label])
    t.node(paths["pru0"], None, 'firmware-name = "am335x-pru0-fw"')
    t.node(paths["pru1"], None, 'firmware-name = "am335x-pru1-fw"')
    ctl = paths["am33xx_pinmux"]
    for pin in helpers:
        off, default_mode, states = HELPERS[pin]
        if family == "4.19":
            states = states[:4] + ["gpio_input"] + states[4:]
        refs = []
        for i, state in enumerate(states):
            label = "%s_%s_pin" % (pin, state)
            mode = default_mode if state == "default" else MODE[state]
            group(t, ctl, label, "pinmux_" + label, [(off, 0x20 | mode)])
            refs.append('pinctrl-%d = <&%s>' % (i, label))
        names = ", ".join('"%s"' % s for s in states)
        t.node("/ocp/%s_pinmux" % pin, None, 'compatible = "bone-pinmux-helper"',
               'status = "okay"', "pinctrl-names = %s" % names, *refs)
    return t


# pinctrl offsets of the HDMI framer's and McASP0's groups (Linux
# dt-bindings/pinctrl/am33xx.h AM335X_PIN_*, minus 0x800): xdma_event_intr0
# 0x1b0; lcd_data0..15 0x0a0..0x0dc; lcd_vsync, hsync, pclk, ac_bias_en
# 0x0e0..0x0ec; mcasp0 ahclkx 0x1ac, ahclkr 0x19c, fsx 0x194, aclkx 0x190;
# gpmc_a11 0x06c.
LCD_PADS = [0x1b0] + list(range(0x0a0, 0x0f0, 4))
MCASP0_PADS = [0x1ac, 0x19c, 0x194, 0x190, 0x06c]
# the helpers BeagleBoard's HDMI overlays disable (src/arm/overlays/
# BB-HDMI-TDA998x-00A0.dts, BB-NHDMI-TDA998x-00A0.dts): the LCD pins, and
# with audio the McASP0 pins too
LCD_HELPERS = ["P8_45", "P8_46", "P8_43", "P8_44", "P8_41", "P8_42", "P8_39", "P8_40", "P8_37",
               "P8_38", "P8_36", "P8_34", "P8_35", "P8_33", "P8_31", "P8_32", "P8_27", "P8_29",
               "P8_28", "P8_30"]
AUDIO_HELPERS = ["P9_25", "P9_28", "P9_29", "P9_31"]


def hdmi_overlay(audio):
    """U-Boot's video overlay: BB-HDMI-TDA998x-00A0 (audio) or
    BB-NHDMI-TDA998x-00A0 (no audio), v5.10.x-ti / v6.1.x-ti
    src/arm/overlays/ (v4.19.x-ti-overlays has BB-HDMI-TDA998x-00A0 with
    the same nodes)."""
    t = Tree(plugin=True)
    t.node("&ocp", None, *["%s_pinmux { status = \"disabled\"; }" % p
                            for p in (AUDIO_HELPERS if audio else []) + LCD_HELPERS])
    t.node("&am33xx_pinmux")
    group(t, "&am33xx_pinmux", "nxp_hdmi_bonelt_pins", "nxp_hdmi_bonelt_pins",
          [(p, 0x08) for p in LCD_PADS])
    group(t, "&am33xx_pinmux", "nxp_hdmi_bonelt_off_pins", "nxp_hdmi_bonelt_off_pins",
          [(0x1b0, 0x0f)])
    t.node("&lcdc", None, 'status = "okay"')
    t.node("&i2c0", None, "#address-cells = <1>", "#size-cells = <0>")
    t.node("&i2c0/tda19988@70", "tda19988", 'compatible = "nxp,tda998x"', "reg = <0x70>",
           'pinctrl-names = "default", "off"', "pinctrl-0 = <&nxp_hdmi_bonelt_pins>",
           "pinctrl-1 = <&nxp_hdmi_bonelt_off_pins>")
    if audio:
        group(t, "&am33xx_pinmux", "mcasp0_pins", "mcasp0_pins",
              [(p, 0x20) for p in MCASP0_PADS])
        t.node("&mcasp0", None, 'pinctrl-names = "default"', "pinctrl-0 = <&mcasp0_pins>",
               'status = "okay"')
    return t


def pru_rproc_419_overlay():
    """uboot_overlay_pru=AM335X-PRU-RPROC-4-19-TI-00A0.dtbo (v4.19.x-ti-overlays
    src/arm/overlays/): the PRU-ICSS nodes under &ocp again, enabled."""
    t = Tree(plugin=True)
    t.node("&ocp/pruss-soc-bus@4a326004", None, 'compatible = "ti,am3356-pruss-soc-bus"',
           'status = "okay"')
    t.node("&ocp/pruss-soc-bus@4a326004/pruss@4a300000", None,
           'compatible = "ti,am3356-pruss"', 'status = "okay"')
    t.node("&ocp/pruss-soc-bus@4a326004/pruss@4a300000/pru@4a334000", None,
           'firmware-name = "am335x-pru0-fw"')
    t.node("&ocp/pruss-soc-bus@4a326004/pruss@4a300000/pru@4a338000", None,
           'firmware-name = "am335x-pru1-fw"')
    return t


# ---- AM437x IDK ---------------------------------------------------------------

def idk_base(family):
    """TI's AM437x IDK. "mainline": am4372.dtsi keeps pruss_tm (and so
    pruss0) enabled; am437x-idk-evm.dts claims none of our pads and has no
    pin helpers; gpio5 "okay". "4.19": the IDK's tree enables pruss_soc_bus,
    pruss1: pruss@54400000 and pruss0: pruss@54440000 (the bus node's name is
    not in the IDK file: the AM335x tree's pattern, pruss-soc-bus@<sysc>, is
    used). The IDK's i2c0 group (0x188, 0x18c: next to our 0x190, 0x194)
    stands for the claims around our pads."""
    t = Tree()
    t.node("/chosen")
    if family == "mainline":
        ocp = "/ocp"
        pinmux = L4_WKUP_SCM + "/pinmux@800"  # am437x-l4.dtsi: as on the AM335x
        i2c0 = ocp + "/interconnect@44c00000/segment@200000/target-module@b000/i2c@0"
        gpio5 = ocp + "/interconnect@48000000/segment@100000/target-module@22000/gpio@0"
        t.node(ocp + "/target-module@54400000", "pruss_tm")
        t.node(ocp + "/target-module@54400000/pruss@0", "pruss1")
        t.node(ocp + "/target-module@54400000/pruss@40000", "pruss0")
        t.node(ocp + "/target-module@54400000/pruss@40000/pru@74000", "pru0_0",
               'firmware-name = "am437x-pru0_0-fw"')
    else:
        ocp = "/ocp@44000000"
        pinmux = ocp + "/l4_wkup@44c00000/scm@210000/pinmux@800"
        i2c0 = ocp + "/i2c@44e0b000"
        gpio5 = ocp + "/gpio@48322000"
        bus = ocp + "/pruss-soc-bus@54426004"
        t.node(bus, "pruss_soc_bus", 'status = "okay"')
        t.node(bus + "/pruss@54400000", "pruss1", 'status = "okay"')
        t.node(bus + "/pruss@54440000", "pruss0", 'status = "okay"')
        t.node(bus + "/pruss@54440000/pru@54474000", "pru0_0",
               'firmware-name = "am437x-pru0_0-fw"')
    controller(t, pinmux, "am43xx_pinmux")
    group(t, pinmux, "i2c0_pins_default", "i2c0_pins_default", [(0x188, 0x40000), (0x18c, 0x40000)])
    t.node(i2c0, "i2c0", 'status = "okay"', 'pinctrl-names = "default"',
           "pinctrl-0 = <&i2c0_pins_default>")
    t.node(gpio5, "gpio5", "gpio-controller", "#gpio-cells = <2>", 'status = "okay"')
    return t


# ---- the cases ----------------------------------------------------------------

# name, base tree, overlay, the overlays U-Boot applies after it (in its
# order: addr4, then video, then pru), the pads two nodes must claim (empty:
# none), and why. U-Boot's order is BeagleBoard U-Boot's uname_boot
# (include/environment npi_common.h: uboot_overlay_addr0..7, emmc, video,
# wireless, adc, pru).
def cases():
    bbb = lambda fam, helpers: am335x_base(fam, BBB_PINS if helpers else [])  # noqa: E731
    pb = lambda fam: am335x_base(fam, PB_PINS)  # noqa: E731
    hdmi, nhdmi, rproc = hdmi_overlay(True), hdmi_overlay(False), pru_rproc_419_overlay()
    out = []
    # 5.10-ti: am335x-boneblack-uboot.dts includes bbb-bone-buses.dtsi, which
    # includes am335x-bone-common-univ.dtsi: helpers with the universal cape
    # off too. 6.1-ti: only am335x-boneblack-uboot-univ.dts has them.
    for ver, fam, helpers_off in (("5.10-ti", "ti", True), ("6.1-ti", "ti", False),
                                  ("4.19-ti", "4.19", False)):
        after = [rproc] if fam == "4.19" else []
        for univ in (True, False):
            base = "BBB %s universal cape %s" % (ver, "on" if univ else "off")
            helpers = univ or helpers_off
            out += [
                (base + ", PRU0, uEnv.txt as docs/hardware.md (audio off)",
                 bbb(fam, helpers), "BB-BISS-PRU0-00A0", [nhdmi] + after, set()),
                (base + ", PRU0, HDMI audio left on", bbb(fam, helpers), "BB-BISS-PRU0-00A0",
                 [hdmi] + after, {0x190, 0x194}),
                (base + ", PRU0+PRU1, uEnv.txt as docs/hardware.md (video off)",
                 bbb(fam, helpers), "BB-BISS-PRU01-00A0", after, set()),
                (base + ", PRU0+PRU1, HDMI video left on", bbb(fam, helpers),
                 "BB-BISS-PRU01-00A0", [nhdmi] + after, {0x0a0, 0x0a4}),
            ]
        out.append(("PocketBeagle %s" % ver, pb(fam), "PB-BISS-PRU0-00A0", after, set()))
    for fam in ("mainline", "4.19"):
        out.append(("AM437x IDK %s" % fam, idk_base(fam), "AM437X-IDK-BISS-00A0", [], set()))
    return out


# the PRU-ICSS node each overlay's pins hang on, per base family
def pruss_path(tree, label):
    for path, (lab, _props, _children) in tree.nodes.items():
        if lab == label:
            return path
    raise KeyError(label)
