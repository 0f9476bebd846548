"""Write the crafted bad inputs of the fuzz corpora (fuzz/corpus/<target>/bad-*): for each
target, made from its seeds, the damage its input is most likely to meet: truncations and
wrong lengths, bad checksums, huge counts, numbers that are not finite, deep nesting, ids
outside the set, frames out of order. The replays (ctest -L fuzz) run them in the sanitized
test build; libFuzzer starts from them too. Same seeds, same files.

Usage: python fuzz/craft_inputs.py [--check]   (--check: fail when a file differs)
"""

import argparse
import os
import struct
import sys

import msgpack

CORPUS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "corpus")


def seed(target, name):
    with open(os.path.join(CORPUS, target, name), "rb") as f:
        return f.read()


def truncations(data):
    return {
        "empty": b"",
        "one-byte": data[:1],
        "half": data[: len(data) // 2],
        "minus-one": data[:-1],
    }


def replace_first(data, old, new):
    i = data.find(old)
    assert i >= 0, old
    return data[:i] + new + data[i + len(old) :]


def config():
    cfg = seed("config", "seed-harvest.cfg")
    out = truncations(cfg)
    out["nan"] = replace_first(cfg, b"vehicle.speed = 0.1", b"vehicle.speed = nan")
    out["inf"] = replace_first(cfg, b"vehicle.speed = 0.1", b"vehicle.speed = inf")
    out["overflow"] = replace_first(cfg, b"vehicle.speed = 0.1", b"vehicle.speed = 1e999")
    out["no-equals"] = replace_first(cfg, b"vehicle.speed = 0.1", b"vehicle.speed 0.1")
    out["twice"] = cfg + b"vehicle.speed = 0.2\n"
    out["unknown-key"] = cfg + b"vehicle.warp = 9\n"
    out["long-line"] = cfg + b"row.length = " + b"9" * 5000 + b"\n"
    out["nul-byte"] = replace_first(cfg, b"vehicle.speed = 0.1", b"vehicle.speed = 0\x001")
    return out


def cost_table():
    tab = seed("cost_table", "seed-left.bin")
    out = truncations(tab)
    out["header-only"] = tab[:64]
    out["trailing-byte"] = tab + b"\x00"
    out["crc-flipped"] = tab[:-1] + bytes([tab[-1] ^ 0x01])
    # the first axis count (after the magic, version and dims) made huge
    huge = bytearray(tab)
    huge[12:16] = struct.pack("<I", 0xFFFFFFFF)
    out["huge-count"] = bytes(huge)
    zero = bytearray(tab)
    zero[12:16] = struct.pack("<I", 0)
    out["zero-count"] = bytes(zero)
    nan = bytearray(tab)
    nan[40:48] = struct.pack("<d", float("nan"))
    out["nan-origin"] = bytes(nan)
    return out


def plan_json(target):
    plan = seed(target, "seed-test-plan.json")
    out = truncations(plan)
    out["deep-nesting"] = b"[" * 20000 + b"]" * 20000
    out["deep-object"] = b'{"a":' * 5000 + b"1" + b"}" * 5000
    out["overflow"] = replace_first(plan, b'"row_length_m": 2.000', b'"row_length_m": 1e999')
    out["nan"] = replace_first(plan, b'"row_length_m": 2.000', b'"row_length_m": NaN')
    out["negative"] = replace_first(plan, b'"row_length_m": 2.000', b'"row_length_m": -2.0')
    out["bad-utf8"] = replace_first(plan, b'"fov"', b'"f\xff\xfev"')
    out["version-99"] = replace_first(plan, b'"version": 2', b'"version": 99')
    out["trailing-garbage"] = plan + b"}{"
    return out


def fruit_map():
    fm = seed("fruit_map", "seed-map-checked")
    out = truncations(fm)
    out["nan"] = replace_first(fm, b"-0.3620", b"nan")
    out["inf"] = replace_first(fm, b"-0.3620", b"-inf")
    out["id-outside-the-set"] = replace_first(fm, b"L000,", b"L 0*0,")
    out["id-too-long"] = replace_first(fm, b"L000,", b"L" + b"0" * 200 + b",")
    out["side-x"] = replace_first(fm, b"L000,L,", b"L000,X,")
    out["short-row"] = replace_first(fm, b"L000,L,-0.3620,0.2258,", b"L000,L,")
    out["duplicate-id"] = fm + fm.split(b"\n")[1] + b"\n"
    out["no-header"] = b"\n".join(fm.split(b"\n")[1:])
    return out


def journal():
    # the target's first byte: bit 0 set, every record's checksum is made right again, so
    # a bad field is read as a field and not refused as damage
    j = seed("journal", "seed-full-0")
    body = j[1:]
    out = {f"{k}": v for k, v in truncations(j).items()}
    resign = b"\x01"
    out["crc-wrong"] = b"\x00" + replace_first(body, b"*6a972599", b"*6a972598")
    out["crc-upper"] = b"\x00" + replace_first(body, b"*6a972599", b"*6A972599")
    out["pick-outside"] = resign + replace_first(body, b"C R 2 a=1", b"C R 99999 a=1")
    out["id-outside-the-set"] = resign + replace_first(body, b"C R 2 a=1", b"C R Z*9 a=1")
    out["attempt-huge"] = resign + replace_first(body, b"C R 2 a=1", b"C R 2 a=4294967296")
    out["time-nan"] = resign + replace_first(body, b"t=4.341", b"t=nan")
    out["outcome-first"] = resign + replace_first(
        body, b"C R 2 a=1 t=6.888", b"F R 2 picked ok a=1 t=6.888"
    )
    out["halt-unknown"] = resign + body + b"H tired t=99.0 *00000000\n"
    out["stop-huge"] = resign + replace_first(body, b"S 0 t=4.341", b"S 4294967296 t=4.341")
    return out


def op_stream(target, names):
    """Operation-coded targets: the seeds' operations reversed (out of order) and thinned."""
    out = {}
    for name in names:
        data = seed(target, name)
        stem = name.removeprefix("seed-")
        out[f"{stem}-reversed"] = data[:1] + data[1:][::-1]
        out[f"{stem}-every-other"] = data[::2]
    out.update(truncations(seed(target, names[0])))
    return out


def udp_wire():
    def pack(**fields):
        msg = {
            "timestamp": 1.0,
            "arbitration_id": 0x21,
            "is_extended_id": False,
            "is_remote_frame": False,
            "is_error_frame": False,
            "channel": None,
            "dlc": 5,
            "is_fd": False,
            "bitrate_switch": False,
            "error_state_indicator": False,
            "data": b"\x01\x02\x03\x04\x05",
        }
        msg.update(fields)
        return msgpack.packb(msg, use_bin_type=True)

    good = pack()
    out = truncations(good)
    out["dlc-beyond-data"] = pack(dlc=8)
    out["dlc-15"] = pack(dlc=15, data=b"\x00" * 8)
    out["data-too-long"] = pack(data=b"\x00" * 64, dlc=8)
    out["id-beyond-11-bits"] = pack(arbitration_id=0x800)
    out["id-beyond-29-bits"] = pack(arbitration_id=0x20000000, is_extended_id=True)
    out["timestamp-huge"] = pack(timestamp=1e300)
    out["timestamp-nan"] = pack(timestamp=float("nan"))
    out["id-negative"] = pack(arbitration_id=-1)
    out["wrong-types"] = pack(arbitration_id="0x21", data=[1, 2])
    out["deep-nesting"] = b"\x91" * 10000 + b"\xc0"
    out["not-a-map"] = msgpack.packb([1, 2, 3])
    out["fd-frame"] = pack(is_fd=True, dlc=12, data=b"\x00" * 12)
    return out


def slcan():
    """SLCAN text as the firmware's UART delivers it (0xFF marks an overrun there)."""
    out = truncations(seed("slcan", "seed-stream"))
    out["dlc-9"] = b"t12390011223344556677\r"
    out["dlc-not-hex"] = b"t123G00\r"
    out["id-beyond-11-bits"] = b"t8001AA\r"
    out["id-beyond-29-bits"] = b"T2000000001AA\r"
    out["data-short-of-dlc"] = b"t1238AABB\r"
    out["data-beyond-dlc"] = b"t1231AABBCC\r"
    out["lower-hex-ext"] = b"T1abcdef02aabb\r"
    out["no-cr"] = b"t1232AABB" * 40
    out["long-line"] = b"t" + b"1" * 4000 + b"\r"
    out["overrun-mid-line"] = b"t1232AA\xffBB\rt1231CC\r"
    out["overrun-at-cr"] = b"t1231AA\xff\rt1231CC\r"
    out["nul-bytes"] = b"t123\x00\x001AA\r"
    return out


def crafted():
    return {
        "config": config(),
        "cost_table": cost_table(),
        "exec_plan": plan_json("exec_plan"),
        "plan_json": plan_json("plan_json"),
        "fruit_map": fruit_map(),
        "journal": journal(),
        "exec_step": op_stream("exec_step", ["seed-good-run", "seed-arm-fault"]),
        "udp_wire": udp_wire(),
        "slcan": slcan(),
        "plan_upload": op_stream(
            "plan_upload", ["seed-accepted-running", "seed-order", "seed-truncated"]
        ),
        "exec_online": op_stream("exec_online", ["seed-grows", "seed-repeats", "seed-contradicts"]),
    }


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--check", action="store_true", help="compare, do not write")
    a = p.parse_args(argv)
    stale = 0
    for target, files in crafted().items():
        for name, data in files.items():
            path = os.path.join(CORPUS, target, f"bad-{name}")
            try:
                with open(path, "rb") as f:
                    same = f.read() == data
            except FileNotFoundError:
                same = False
            if a.check:
                if not same:
                    print(f"{path}: not what craft_inputs.py writes", file=sys.stderr)
                    stale += 1
            elif not same:
                with open(path, "wb") as f:
                    f.write(data)
        print(f"{target}: {len(files)} crafted inputs")
    return 1 if stale else 0


if __name__ == "__main__":
    sys.exit(main())
