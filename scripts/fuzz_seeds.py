"""Writes seed inputs for the cargo-fuzz targets into CORPUS/<target>/ (default
fuzz/corpus): one small valid file of each format a target reads, so the
fuzzer starts past the formats' signatures. Run by scripts/fuzz.sh, which
installs what this needs (laspy, lazrs, pye57, openpyxl, odfpy).

For targets whose first byte picks the format (scan_file, chart_workbook,
artifacts), each seed starts with that byte; some seeds are a single part
that the target frames (an E57 file whose checksums it writes, a workbook
part it zips)."""
import os, shutil, struct, sys, tempfile
import numpy as np

root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
corpus = sys.argv[1] if len(sys.argv) > 1 else os.path.join(root, "fuzz", "corpus")
tmp = tempfile.mkdtemp()


def seed(target, name, data, select=None):
    d = os.path.join(corpus, target)
    os.makedirs(d, exist_ok=True)
    with open(os.path.join(d, name), "wb") as f:
        f.write((bytes([select]) if select is not None else b"") + data)


def read(path):
    with open(path, "rb") as f:
        return f.read()


# rvm, att: the fixture plant export.
seed("rvm", "plm-sample.rvm", read(os.path.join(root, "fixtures/plant/plm-sample_11072013.rvm")))
seed("att", "plm-sample.att", read(os.path.join(root, "fixtures/plant/plm-sample_11072013.att")))

# crane_and_lift_toml: the built-in cranes and the demo's lift.
cranes = os.path.join(root, "stages/core/src/cranes")
for name in sorted(os.listdir(cranes)):
    seed("crane_and_lift_toml", name, read(os.path.join(cranes, name)))
# The demo's lift, taken from the demo project's text so the two stay alike.
demo = read(os.path.join(root, "fixtures/src/demo.rs")).decode()
lift = demo[demo.index("[[lift]]\n") + len("[[lift]]\n"):]
seed("crane_and_lift_toml", "lift.toml", lift[:lift.index('"#')].encode())
# The same lift on a spreader beam (rigging.spreader), to reach its check.
rigging = "rigging = { mass_t = 0.5, height_m = 4.0, legs = 2, leg_wll_t = 10.0, shackle_wll_t = 12.0 }"
assert rigging in lift, "the demo's rigging line changed: update the spreader seed"
spreader = rigging[:-2] + ", spreader = { length_m = 8.0, below_hook_m = 2.0, wll_t = 20.0, mass_t = 0.3, top_leg_wll_t = 12.0, top_shackle_wll_t = 12.0, top_pin_axes = [[0.0, 1.0, 0.0], [0.3, 1.0, 0.0]] } }"
seed("crane_and_lift_toml", "lift-spreader.toml", lift[:lift.index('"#')].replace(rigging, spreader).encode())
# ... and on a spreader frame over four corners (rigging.spreader.width_m).
frame = rigging.replace("legs = 2", "legs = 4")[:-2] + ", spreader = { length_m = 8.0, width_m = 3.0, below_hook_m = 2.0, wll_t = 20.0, mass_t = 0.3, top_leg_wll_t = 12.0, top_shackle_wll_t = 12.0 } }"
seed("crane_and_lift_toml", "lift-frame.toml", lift[:lift.index('"#')].replace(rigging, frame).encode())
# ... and with its shackles' pins given (rigging.pin_axes), to reach the side loading.
pins = rigging[:-2] + ", lift_point_wll_t = 11.0, pin_axes = [[0.0, 1.0, 0.0], [0.2, 1.0, 0.1]] }"
seed("crane_and_lift_toml", "lift-pins.toml", lift[:lift.index('"#')].replace(rigging, pins).encode())
# ... and with its centre of gravity known only so well in height.
tol = "cog_tolerance_m = 0.1 }"
assert tol in lift, "the demo's load line changed: update the height-tolerance seed"
seed("crane_and_lift_toml", "lift-cog-height.toml", lift[:lift.index('"#')].replace(tol, "cog_tolerance_m = 0.1, cog_tolerance_z_m = 0.2 }").encode())
# project_toml: the template `liftplan init` writes and the demo's project
# file, taken from their sources.
for name, path, const in [("init.toml", "src/project.rs", "TEMPLATE"), ("demo.toml", "fixtures/src/demo.rs", "PROJECT_TOML")]:
    text, start = read(os.path.join(root, path)).decode(), f'pub const {const}: &str = r#"'
    body = text[text.index(start) + len(start):]
    seed("project_toml", name, body[:body.index('"#;')].encode())
seed("crane_and_lift_toml", "stations.toml", b'[[station]]\nscan = "scan-1"\nx_m = 1.0\ny_m = 2.0\nz_m = 0.5\n'
     b'yaw_deg = 30.0\n\n[[station]]\nscan = "scan-2"\nx_m = -4.0\ny_m = 12.5\n')

# scan_file: first byte 0 las, 1 laz, 2 ply, 3 e57, 4 pts, 5 xyz; 252 and above ptx.
import laspy

rng = np.random.default_rng(1)
n = 40
x, y, z = rng.uniform(0, 10, n), rng.uniform(0, 10, n), rng.uniform(0, 3, n)
for version, fmt, name in [("1.2", 0, "a12.las"), ("1.2", 3, "b12.las"), ("1.4", 6, "c14.las"),
                           ("1.2", 1, "d12.laz"), ("1.4", 7, "e14.laz")]:
    h = laspy.LasHeader(point_format=fmt, version=version)
    h.scales, h.offsets = [0.001] * 3, [0.0] * 3
    las = laspy.LasData(h)
    las.x, las.y, las.z = x, y, z
    las.classification = (np.arange(n) % 3).astype(np.uint8)
    path = os.path.join(tmp, name)
    laz = name.endswith(".laz")
    las.write(path, laz_backend=laspy.LazBackend.Lazrs if laz else None)
    seed("scan_file", name, read(path), 1 if laz else 0)
    # site_cloud: the same files as the stages after scans read site.laz.
    seed("site_cloud", name, read(path))
seed("scan_file", "variable-chunks.laz", read(os.path.join(root, "fixtures/scans/variable-chunks.laz")), 1)
seed("site_cloud", "variable-chunks.laz", read(os.path.join(root, "fixtures/scans/variable-chunks.laz")))

def ply_header(fmt, props):
    return (f"ply\nformat {fmt} 1.0\nelement vertex {n}\n" + "".join(f"property {p}\n" for p in props)
            + "end_header\n").encode()
rgb = ["float x", "float y", "float z", "uchar red", "uchar green", "uchar blue"]
seed("scan_file", "a.ply", ply_header("ascii", rgb)
     + "".join(f"{a:.3f} {b:.3f} {c:.3f} 10 20 30\n" for a, b, c in zip(x, y, z)).encode(), 2)
seed("scan_file", "b.ply", ply_header("binary_little_endian", rgb)
     + b"".join(struct.pack("<fffBBB", a, b, c, 1, 2, 3) for a, b, c in zip(x, y, z)), 2)
seed("scan_file", "c.ply", ply_header("binary_little_endian", ["double x", "double y", "double z"])
     + b"".join(struct.pack("<ddd", a, b, c) for a, b, c in zip(x, y, z)), 2)

import pye57

for name, extra in [("a.e57", False), ("b.e57", True)]:
    path = os.path.join(tmp, name)
    e = pye57.E57(path, mode="w")
    data = {"cartesianX": x[:30], "cartesianY": y[:30], "cartesianZ": z[:30]}
    if extra:
        data["intensity"] = rng.uniform(0, 1, 30)
        grey = rng.integers(0, 255, 30).astype(np.uint8)
        data["colorRed"] = data["colorGreen"] = data["colorBlue"] = grey
    e.write_scan_raw(data, rotation=np.array([1.0, 0, 0, 0]), translation=np.array([1.0, 2.0, 0.5]))
    e.close()
    seed("scan_file", name, read(path), 3)
    # Selector 9: e57, with the target writing the page checksums.
    seed("scan_file", "crc-" + name, read(path), 9)
seed("scan_file", "crc-two-scans.e57", read(os.path.join(root, "fixtures/scans/two-scans.e57")), 9)

seed("scan_file", "a.pts", (f"{n}\n" + "".join(f"{a:.3f} {b:.3f} {c:.3f} -1200 100 120 140\n"
                                              for a, b, c in zip(x, y, z))).encode(), 4)
seed("scan_file", "a.xyz", "".join(f"{a:.3f} {b:.3f} {c:.3f}\n" for a, b, c in zip(x, y, z)).encode(), 5)
# A survey's export whose header names its columns, a point's number first.
seed("scan_file", "survey.csv", ("Point,Easting,Northing,Height\n" + "".join(
    f"{k},{a:.3f},{b:.3f},{c:.3f}\n" for k, (a, b, c) in enumerate(zip(x, y, z)))).encode(), 5)
seed("scan_file", "b.xyz", "".join(f"{a:.3f},{b:.3f},{c:.3f},200,100,50\n" for a, b, c in zip(x, y, z)).encode(), 5)
seed("scan_file", "bom-a.xyz", b"\xef\xbb\xbf" + read(os.path.join(corpus, "scan_file", "a.xyz"))[1:], 5)
# PTX: two scans of a 5 x 8 grid, the second turned 30 degrees and moved,
# with colour, a cell of no return in each.
def ptx_scan(turn_deg, move, colour):
    c, s = np.cos(np.radians(turn_deg)), np.sin(np.radians(turn_deg))
    rows = [(c, s, 0.0), (-s, c, 0.0), (0.0, 0.0, 1.0)]
    head = "5\n8\n" + "{} {} {}\n".format(*move) + "".join("{} {} {}\n".format(*r) for r in rows)
    head += "".join("{} {} {} 0\n".format(*r) for r in rows) + "{} {} {} 1\n".format(*move)
    pts = "".join((f"{a:.3f} {b:.3f} {c_:.3f} 0.5" + (" 10 20 30" if colour else "") + "\n")
                  if k else ("0 0 0 0.5" + (" 0 0 0" if colour else "") + "\n")
                  for k, (a, b, c_) in enumerate(zip(x, y, z)))
    return head + pts
seed("scan_file", "a.ptx", (ptx_scan(0.0, (0.0, 0.0, 0.0), False) + ptx_scan(30.0, (12.5, -3.0, 0.25), True)).encode(), 252)

# chart_workbook: first byte 0 xlsx, 1 xls, 2 xlsb, 3 ods.
import openpyxl
from odf.opendocument import OpenDocumentSpreadsheet
from odf.table import Table, TableCell, TableRow
from odf.text import P

booms, radii = [20.0, 30.0, 40.0], [3.0, 5.0, 8.0, 12.0]
cap = lambda r, b: round(400 / (r + 2) * (30 / b), 1) if r < b - 2 else None
rows = [["Main boom 360, counterweight 20 t, capacities in t"], [], ["Radius (m)", "Boom length (m)"],
        [None] + booms] + [[r] + [cap(r, b) for b in booms] for r in radii]
wb = openpyxl.Workbook()
ws = wb.active
ws.title = "Main boom 360"
for row in rows:
    ws.append(row)
imperial = wb.create_sheet("Imperial")
for row in [["Capacities in lb"], [], ["Radius (ft)", "Boom length (ft)"], [None, 66, 98],
            [10, 40000, 30000], [20, 20000, "15,000*"]]:
    imperial.append(row)
path = os.path.join(tmp, "chart.xlsx")
wb.save(path)
seed("chart_workbook", "chart.xlsx", read(path), 0)
# The same chart with its numbers as text, with decimal commas and one
# that shows no mark of its own ("12,500"), as typed in a German Excel.
as_text = openpyxl.Workbook()
ws = as_text.active
ws.title = "Main boom 360"
for row in rows:
    ws.append([str(v).replace(".", ",") if isinstance(v, float) else v for v in row])
ws["C6"] = "12,500"
path = os.path.join(tmp, "chart-text.xlsx")
as_text.save(path)
seed("chart_workbook", "chart-text.xlsx", read(path), 0)
# Radii and boom lengths pasted from a PDF with their unit in the cell,
# one cell in feet among metres.
ws["A5"], ws["B4"], ws["C4"], ws["A8"] = "3,0 m", "20 m", "30m", "12 ft"
path = os.path.join(tmp, "chart-units.xlsx")
as_text.save(path)
seed("chart_workbook", "chart-units.xlsx", read(path), 0)
# Text saved with a workbook's name, as web portals export "xls" files.
seed("chart_workbook", "csv-as-xlsx", b"Radius;20;30\r\n3;49;39\r\n5;34,8;29,4\r\n", 0)
seed("chart_workbook", "html-as-xls", b"<html><body><table><tr><td>Radius</td><td>20</td></tr></table></body></html>", 1)
# Formulas openpyxl stores without their values.
ws["B6"], ws["D4"] = "=B7*1.5", "=C4+10"
path = os.path.join(tmp, "chart-formulas.xlsx")
as_text.save(path)
seed("chart_workbook", "chart-formulas.xlsx", read(path), 0)
def ods_seed(name, formula_row=None):
    """The chart as an ods seed; in row `formula_row`, its empty cells hold a
    formula odfpy stores without its value."""
    doc = OpenDocumentSpreadsheet()
    table = Table(name="Main boom 360")
    for k, row in enumerate(rows):
        tr = TableRow()
        for v in row:
            if v is None:
                cell = TableCell(formula="of:=[.B5]*1.5") if k == formula_row else TableCell()
            else:
                cell = TableCell(valuetype="float", value=v) if isinstance(v, float) else TableCell(valuetype="string")
                cell.addElement(P(text=str(v)))
            tr.addElement(cell)
        table.addElement(tr)
    doc.spreadsheet.addElement(table)
    path = os.path.join(tmp, name)
    doc.save(path)
    seed("chart_workbook", name, read(path), 3)


ods_seed("chart.ods")
ods_seed("chart-formula.ods", formula_row=4)
# The xls and xlsb fixtures (xlwt's BIFF8 in a compound file; BIFF12 records
# written by make_chart_xlsb.py).
seed("chart_workbook", "chart.xls", read(os.path.join(root, "fixtures/charts/chart.xls")), 1)
xlsb = os.path.join(root, "fixtures/charts/chart.xlsb")
seed("chart_workbook", "chart.xlsb", read(xlsb), 2)
# Selectors 4 to 7: one part, zipped by the target into a workbook.
import zipfile
with zipfile.ZipFile(os.path.join(tmp, "chart.ods")) as z:
    seed("chart_workbook", "content.xml", z.read("content.xml"), 4)
with zipfile.ZipFile(os.path.join(tmp, "chart.xlsx")) as z:
    seed("chart_workbook", "sheet1.xml", z.read("xl/worksheets/sheet1.xml"), 5)
# openpyxl writes its strings inline; the shared strings the target's sheet names:
sst = "".join(f"<si><t>{t}</t></si>" for t in ["Main boom, capacities in t", "Radius (m)", "Boom length (m)"])
seed("chart_workbook", "sharedStrings.xml", ('<?xml version="1.0" encoding="UTF-8"?><sst xmlns='
     f'"http://schemas.openxmlformats.org/spreadsheetml/2006/main" count="3" uniqueCount="3">{sst}</sst>').encode(), 6)
with zipfile.ZipFile(xlsb) as z:
    seed("chart_workbook", "sheet1.bin", z.read("xl/worksheets/sheet1.bin"), 7)

# artifacts: first byte 0 raw bytes, 1 depth-map payload, 2 mesh payload
# (the target frames 1 and 2 as valid artifacts).
def s(text):
    b = text.encode()
    return struct.pack("<I", len(b)) + b

mdm = struct.pack("<dddII", 0.0, 0.0, 1.0, 2, 2) + b"\x00" + struct.pack("<Q", 2) + s("ground") + s("PIPE-RACK-2")
mdm += struct.pack("<Q", 5) + struct.pack("<5I", 0, 1, 1, 3, 3)
mdm += struct.pack("<Q", 3) + struct.pack("<ffI", 0, 0.1, 0) + struct.pack("<ffI", 1, 2, 1) + struct.pack("<ffI", 3, 4, 1)
seed("artifacts", "mdm-payload", mdm, 1)
mesh = struct.pack("<Q", 1) + s("/RACK") + struct.pack("<Q", 1) + struct.pack("<IB", 0, 1)
mesh += struct.pack("<Q", 3) + struct.pack("<9d", 0, 0, 0, 1, 0, 0, 0, 1, 2)
mesh += struct.pack("<Q", 1) + struct.pack("<4I", 0, 1, 2, 0)
seed("artifacts", "mesh-payload", mesh, 2)

# registration_memo: first byte even a whole memo file, odd a payload the
# target frames. Two answers: a key, a length, the answer's bytes.
memo = struct.pack("<Q", 2)
memo += bytes(range(32)) + struct.pack("<Q", 16) + struct.pack("<2d", 0.5, 0.001)
memo += bytes(range(32, 64)) + struct.pack("<Q", 0)
seed("registration_memo", "payload", memo, 1)

# plant_mesh: first byte 0 obj, 1 ply, 2 stl, 3 gltf, 4 glb. A tetrahedron each.
import base64, json

tet_v = [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0)]
tet_f = [(0, 2, 1), (0, 1, 3), (0, 3, 2), (1, 2, 3)]
seed("plant_mesh", "tet.obj", ("o PIPE-1\n" + "".join(f"v {a} {b} {c}\n" for a, b, c in tet_v)
                               + "".join(f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in tet_f)).encode(), 0)
seed("plant_mesh", "tet.ply", (f"ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
                               f"property float z\nelement face 4\nproperty list uchar int vertex_indices\nend_header\n"
                               + "".join(f"{a} {b} {c}\n" for a, b, c in tet_v)
                               + "".join(f"3 {a} {b} {c}\n" for a, b, c in tet_f)).encode(), 1)
seed("plant_mesh", "tet-ascii.stl", ("solid tet\n" + "".join(
    "facet normal 0 0 0\nouter loop\n" + "".join(f"vertex {x} {y} {z}\n" for x, y, z in (tet_v[i] for i in f))
    + "endloop\nendfacet\n" for f in tet_f) + "endsolid tet\n").encode(), 2)
# The text ones again as a Windows tool saves them, with a byte order mark.
BOM = b"\xef\xbb\xbf"
for name, sel in [("tet.obj", 0), ("tet.ply", 1), ("tet-ascii.stl", 2)]:
    seed("plant_mesh", "bom-" + name, BOM + read(os.path.join(corpus, "plant_mesh", name))[1:], sel)
seed("plant_mesh", "tet-binary.stl", b"\0" * 80 + struct.pack("<I", 4) + b"".join(
    struct.pack("<3f", 0, 0, 0) + b"".join(struct.pack("<3f", *tet_v[i]) for i in f) + b"\0\0" for f in tet_f), 2)
positions = b"".join(struct.pack("<3f", *v) for v in tet_v)
indices = b"".join(struct.pack("<3H", *f) for f in tet_f)
binary = positions + indices
def gltf_json(uri):
    buffer = {"byteLength": len(binary)}
    if uri:
        buffer["uri"] = uri
    return {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
            "nodes": [{"mesh": 0, "name": "VESSEL-1", "translation": [1.0, 0.0, 0.0]}],
            "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
            "buffers": [buffer],
            "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": len(positions)},
                            {"buffer": 0, "byteOffset": len(positions), "byteLength": len(indices)}],
            "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
                           "min": [0, 0, 0], "max": [1, 1, 1]},
                          {"bufferView": 1, "componentType": 5123, "count": 12, "type": "SCALAR"}]}
uri = "data:application/octet-stream;base64," + base64.b64encode(binary).decode()
seed("plant_mesh", "tet.gltf", json.dumps(gltf_json(uri)).encode(), 3)
seed("plant_mesh", "bom-tet.gltf", BOM + json.dumps(gltf_json(uri)).encode(), 3)
js = json.dumps(gltf_json(None)).encode()
js += b" " * (-len(js) % 4)
body = binary + b"\0" * (-len(binary) % 4)
glb = (struct.pack("<I", len(js)) + b"JSON" + js
       + struct.pack("<I", len(body)) + b"BIN\0" + body)
seed("plant_mesh", "tet.glb", b"glTF" + struct.pack("<II", 2, 12 + len(glb)) + glb, 4)

# kept_plans: two kept plans of lift V-101 (as the revisions tests write
# them), their records of inputs, and out/plan.json naming the second; the
# five files split at 0xFF.
def kept_plan(revision, gross_kg, swing):
    steps = [{"operation": op, "amount": amount, "unit": unit}
             for op, amount, unit in [("Hoist up", 0.5, "m"), ("Swing", swing, "deg"), ("Lower", 0.5, "m")]]
    return {"lift": "V-101", "gross_kg": gross_kg, "crane_model": "AC 700", "steps": steps,
            "planning": {"plan_ms": 1200.0, "box_queries": 5.0e5},
            "summary": {"revision": revision, "validated": True, "steps": len(steps),
                        "highest_pad": [1, {"load_kg": 104200.0, "pad": "RearLeft"}], "obstacles": []}}
def made_from(settings, scan):
    # With the parts of the settings the lifts are in (revisions::add_lift_settings).
    parts = {"settings of lift V-101": "aa" + settings, "settings of lift P-7": "bb", "settings besides the lifts": "cc"}
    return {"inputs": {"code": "31ee", "settings": settings, "upstream:scans/site.laz": "1f90", **parts},
            "stages": {"scans": {"file:scans/a.laz": scan, "settings": "s1"},
                       "charts": {"file:charts/c.xlsx": "c1", "settings": settings, **parts}}}
files = [{"lifts": [kept_plan("0000000a", 16819.0, 30.0)]}, {"lifts": [kept_plan("0000000b", 17319.0, 31.0)]},
         made_from("ecaa", "aa"), made_from("ecab", "a2"), {"lifts": [kept_plan("0000000b", 17319.0, 31.0)]}]
seed("kept_plans", "two-plans", b"\xff".join(json.dumps(f).encode() for f in files))

# capacity_csv: the charts stage's table as it writes it (two configurations,
# a blank cell left out, a cell name quoted for its comma).
seed("capacity_csv", "capacity.csv", b"""config,boom_m,radius_m,capacity_kg,cell
Main boom 360,12.0,3.0,50000.0,chart.xlsx [Main!B2]
Main boom 360,12.0,4.0,40000.0,chart.xlsx [Main!B3]
Main boom 360,20.0,4.0,35000.0,chart.xlsx [Main!C3]
Main boom 360,12.0,6.0,30000.0,chart.xlsx [Main!B4]
Main boom 360,20.0,6.0,28000.0,chart.xlsx [Main!C4]
Jib,0.0,10.0,6000.0,"tower.xlsx [Jib, 60 m!B2]"
""")

# plan_document: the demo's plan.json (kept in fuzz/seeds/, which the demo's
# end-to-end test checks the docs stage still draws).
for name in sorted(os.listdir(os.path.join(root, "fuzz", "seeds", "plan_document"))):
    seed("plan_document", name, read(os.path.join(root, "fuzz", "seeds", "plan_document", name)))

# chart_json: the demo's chart.json (kept in fuzz/seeds/, which liftplan-core's
# chart_json tests read, so the seed stays one the reader takes).
for name in sorted(os.listdir(os.path.join(root, "fuzz", "seeds", "chart_json"))):
    seed("chart_json", name, read(os.path.join(root, "fuzz", "seeds", "chart_json", name)))

# plant_json: the demo's plant.json (kept in fuzz/seeds/, which liftplan-core's
# tests read, so the seed stays one the reader takes).
for name in sorted(os.listdir(os.path.join(root, "fuzz", "seeds", "plant_json"))):
    seed("plant_json", name, read(os.path.join(root, "fuzz", "seeds", "plant_json", name)))

# stage_records: the demo's registration.json, a NUL, and its lifts.json (kept
# in fuzz/seeds/, which the scans and charts crates' tests read); then the
# same with a scan left out, one warned of, the reference levelled by its
# ground and the lift on a chart of one column, so that each is drawn.
import json
records = os.path.join(root, "fuzz", "seeds", "stage_records")
registration, lifts = read(os.path.join(records, "registration.json")), read(os.path.join(records, "lifts.json"))
seed("stage_records", "demo", registration + b"\0" + lifts)
said = json.loads(registration)
said["scans"][0]["method"] = "reference, levelled by its ground (where that slopes, the site frame slopes with it)"
said["scans"][1]["warning"] = "scan 'scan-2' was moved 0.06 m by the last alignment"
said["scans"][2]["registered"] = False
charted = json.loads(lifts)
charted["lifts"][0]["one_column_for_boom_m"] = 40.0
seed("stage_records", "demo-all-said", json.dumps(said).encode() + b"\0" + json.dumps(charted).encode())

shutil.rmtree(tmp)
print(f"seeds written under {corpus}")
