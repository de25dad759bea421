/* biss_cd_cmd.c - what each BiSS command does (host/CD.md, "Commands"):
 * the BiSS C command table as Microchip's documentation of the dsPIC33A
 * BiSS peripheral gives it (section "Command Communication", tables
 * "Broadcast Command Options" and "Addressed Command Options":
 * https://onlinedocs.microchip.com/oxy/GUID-E48B4A26-F201-4F0A-BCBA-16461582816A-en-US-3/GUID-B848ACF0-2596-491B-94D8-E75D08033CE6.html).
 * A broadcast (IDS = 0) goes to every slave; an addressed command to the
 * slaves whose IDS bit is set. */
#include "biss_cd.h"

const char biss_cd_cmd_source[] =
    "Microchip's dsPIC33A BiSS peripheral documentation, \"Command Communication\": tables "
    "\"Broadcast Command Options\" and \"Addressed Command Options\" (host/CD.md, \"Commands\")";

static const biss_cd_cmd_info broadcast[4] = {
    {"switches the data channels of every slave off", true},
    {"switches register and command communication of every slave on", false},
    {"switches every bus coupler to bypass", true},
    {"reserved", true},
};

static const biss_cd_cmd_info addressed[4] = {
    {"switches the data channel of each addressed slave on", false},
    {"switches register and command communication of each addressed slave off", true},
    {"switches the addressed bus couplers from bypass to line operation", true},
    {"does what each addressed slave's maker defines", true},
};

const biss_cd_cmd_info *biss_cd_cmd_effect(uint8_t ids, unsigned cmd) {
    if (cmd > 3) {
        return NULL;
    }
    return ids ? &addressed[cmd] : &broadcast[cmd];
}
