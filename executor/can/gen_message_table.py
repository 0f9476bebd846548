#!/usr/bin/env python3
"""Generate the C table of every DBC message (hv/can_messages.h) from harvest.dbc.

Usage: gen_message_table.py DBC OUT.c

Each entry wraps the cantools-generated functions (generate_c_source --database-name
harvest_can), whose names cantools derives with camel_to_snake_case; we use the same
helper so the names cannot drift.
"""

import sys

import cantools
from cantools.database.can.c_source import camel_to_snake_case

PREFIX = "harvest_can"


def emit(db):
    out = [
        "/* Generated from harvest.dbc by gen_message_table.py: do not edit. */",
        '#include "hv/can_messages.h"',
        "",
        "#include <string.h>",
        "",
        '#include "harvest_can.h"',
        "",
    ]
    entries = []
    for m in db.messages:
        msg = camel_to_snake_case(m.name)
        fn = f"{PREFIX}_{msg}"
        sigs = [(s.name, camel_to_snake_case(s.name)) for s in m.signals]
        names = ", ".join(f'"{n}"' for n, _ in sigs)
        out.append(f"static const char *const {msg}_signals[] = {{{names}}};")
        mins = ", ".join(
            repr(float(s.minimum if s.minimum is not None else -1e308)) for s in m.signals
        )
        maxs = ", ".join(
            repr(float(s.maximum if s.maximum is not None else 1e308)) for s in m.signals
        )
        out.append(f"static const double {msg}_min[] = {{{mins}}};")
        out.append(f"static const double {msg}_max[] = {{{maxs}}};")
        out.append(f"static int {msg}_pack(uint8_t *dst, const double *v)\n{{")
        out.append(f"    struct {fn}_t s;\n    {fn}_init(&s);")
        for i, (_, snake) in enumerate(sigs):
            out.append(f"    s.{snake} = {fn}_{snake}_encode(v[{i}]);")
        out.append(f"    return {fn}_pack(dst, &s, {m.length});\n}}")
        out.append(f"static int {msg}_unpack(const uint8_t *src, size_t len, double *v)\n{{")
        out.append(f"    struct {fn}_t s;\n    int r = {fn}_unpack(&s, src, len);")
        out.append("    if (r < 0)\n        return r;")
        for i, (_, snake) in enumerate(sigs):
            out.append(f"    v[{i}] = {fn}_{snake}_decode(s.{snake});")
        out.append("    return r;\n}")
        entries.append(
            f'    {{"{m.name}", 0x{m.frame_id:03x}u, {m.length}, {len(sigs)}, '
            f"{msg}_signals, {msg}_min, {msg}_max, {msg}_pack, {msg}_unpack}},"
        )
        if len(sigs) > 16:
            raise SystemExit(f"{m.name}: {len(sigs)} signals > HV_CAN_MAX_SIGNALS")
    out.append("")
    out.append("const hv_can_message_desc_t hv_can_messages[] = {")
    out.extend(entries)
    out.append("};")
    out.append(f"const size_t hv_can_n_messages = {len(entries)};")
    out.append("""
const hv_can_message_desc_t *hv_can_message_by_name(const char *name)
{
    for (size_t i = 0; name && i < hv_can_n_messages; i++)
        if (strcmp(hv_can_messages[i].name, name) == 0)
            return &hv_can_messages[i];
    return NULL;
}

const hv_can_message_desc_t *hv_can_message_by_id(uint32_t id)
{
    for (size_t i = 0; i < hv_can_n_messages; i++)
        if (hv_can_messages[i].id == id)
            return &hv_can_messages[i];
    return NULL;
}

hv_status_t hv_can_message_check(const hv_can_frame_t *frame)
{
    if (!frame)
        return HV_ERR_ARG;
    if (frame->flags != 0)
        return (hv_status_t)HV_CAN_ERR_DECODE;
    const hv_can_message_desc_t *m = hv_can_message_by_id(frame->id);
    if (!m || m->length != frame->dlc)
        return (hv_status_t)HV_CAN_ERR_DECODE;
    return HV_OK;
}""")
    return "\n".join(out) + "\n"


def main(argv):
    if len(argv) != 3 or argv[1] in ("-h", "--help"):
        print(__doc__.strip())
        return 0 if len(argv) == 2 else 2
    db = cantools.database.load_file(argv[1], strict=True)
    text = emit(db)
    with open(argv[2], "w", encoding="utf-8") as f:
        f.write(text)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
