#!/usr/bin/env python3
"""Peer side of the scans benchmark (see scripts/bench_scans.sh).

Times, on the files `bench_scans generate` wrote, what liftplan's bench_scans
times: LAZ decode (laspy with the lazrs backend, single and multi-threaded),
voxel-centroid thinning (Open3D voxel_down_sample on the decoded points) and
point-to-plane ICP (Open3D registration_icp with the same distance schedule,
start pose and iteration cap). Prints one JSON object per measurement.
"""
import json
import sys
import time

import numpy as np


def decode(path):
    import laspy

    out = []
    for name, backend in [("laspy+lazrs (1 thread)", laspy.LazBackend.Lazrs),
                          ("laspy+lazrs (parallel)", laspy.LazBackend.LazrsParallel)]:
        t = time.perf_counter()
        las = laspy.read(path, laz_backend=backend)
        # Scaled coordinates, as liftplan delivers them.
        z = np.asarray(las.z)
        s = time.perf_counter() - t
        n = len(z)
        out.append({"tool": name, "op": "decode", "points": n, "seconds": s, "points_per_s": n / s,
                    "z_mean": float(z.mean())})
    return out


def voxel(path, edge):
    import laspy
    import open3d as o3d

    las = laspy.read(path, laz_backend=laspy.LazBackend.LazrsParallel)
    pts = np.ascontiguousarray(np.vstack((las.x, las.y, las.z)).T, dtype=np.float64)
    pcd = o3d.geometry.PointCloud(o3d.utility.Vector3dVector(pts))
    t = time.perf_counter()
    down = pcd.voxel_down_sample(edge)
    s = time.perf_counter() - t
    return [{"tool": "Open3D " + o3d.__version__, "op": "voxel", "points": len(pts), "voxel_m": edge,
             "voxels": len(down.points), "seconds": s}]


def icp(folder):
    import open3d as o3d

    meta = json.load(open(f"{folder}/icp.json"))
    src = o3d.io.read_point_cloud(f"{folder}/{meta['source']}")
    tgt = o3d.io.read_point_cloud(f"{folder}/{meta['target']}")
    truth = np.array(meta["truth"])
    k = meta["normals"]["k"]
    r = meta["normals"]["max_radius_m"]
    t = time.perf_counter()
    for c in (src, tgt):
        c.estimate_normals(o3d.geometry.KDTreeSearchParamHybrid(radius=r, max_nn=k))
        c.orient_normals_towards_camera_location(np.zeros(3))
    normals_s = time.perf_counter() - t
    reg = o3d.pipelines.registration
    rows = []
    # Plain point-to-plane, and with a Huber kernel of the width liftplan uses (d/20).
    variants = [("plain", None), ("Huber d/20", lambda d: reg.HuberLoss(max(d / 20, 0.01)))]
    for (name, kernel), start in [(v, s) for s in ("far", "near") for v in variants]:
        t = time.perf_counter()
        pose = np.array(meta["inits"][start])
        for d in meta["distances_m"]:
            est = (reg.TransformationEstimationPointToPlane() if kernel is None
                   else reg.TransformationEstimationPointToPlane(kernel(d)))
            res = reg.registration_icp(src, tgt, d, pose, est,
                                       reg.ICPConvergenceCriteria(max_iteration=meta["max_iterations_per_distance"]))
            pose = res.transformation
        icp_s = time.perf_counter() - t
        err = np.linalg.inv(pose) @ truth
        ang = np.degrees(np.arccos(np.clip((np.trace(err[:3, :3]) - 1) / 2, -1, 1)))
        ev = reg.evaluate_registration(src, tgt, 0.25, pose)
        rows.append({"tool": f"Open3D {o3d.__version__} ({name})", "op": "icp", "start": start, "source_points": len(src.points),
                     "target_points": len(tgt.points), "normals_seconds": normals_s, "icp_seconds": icp_s,
                     "rotation_error_deg": float(ang),
                     "translation_error_mm": float(np.linalg.norm(err[:3, 3]) * 1000),
                     "fitness_open3d_0.25m": ev.fitness, "rmse_mm_open3d_0.25m": ev.inlier_rmse * 1000})
    return rows


def pdal(path, edge):
    """PDAL's LAZ reader to a null writer, then with its voxel-centroid filter.

    Times include PDAL's process start; the voxel time is the difference.
    """
    import subprocess
    import tempfile

    def run(stages):
        with tempfile.NamedTemporaryFile("w", suffix=".json", delete=False) as f:
            json.dump({"pipeline": stages}, f)
        t = time.perf_counter()
        subprocess.run(["pdal", "pipeline", f.name], check=True)
        return time.perf_counter() - t

    read = {"type": "readers.las", "filename": path}
    dec = run([read, {"type": "writers.null"}])
    vox = run([read, {"type": "filters.voxelcentroidnearestneighbor", "cell": edge}, {"type": "writers.null"}])
    import laspy
    n = laspy.open(path).header.point_count
    return [{"tool": "PDAL", "op": "decode", "points": n, "seconds": dec, "points_per_s": n / dec},
            {"tool": "PDAL (centroid-nearest)", "op": "voxel", "points": n, "voxel_m": edge, "seconds": vox - dec}]


def summary(path):
    rows = [json.loads(line) for line in open(path) if line.strip()]
    out = []

    def table(title, head, sel, fmt):
        out.append(f"### {title}\n")
        out.append("| " + " | ".join(head) + " |")
        out.append("|" + "---|" * len(head))
        for r in rows:
            if sel(r):
                out.append("| " + " | ".join(fmt(r)) + " |")
        out.append("")

    lp = {(r["op"], r.get("points", r.get("source_points")), r.get("start")): r for r in rows if r["tool"] == "liftplan"}
    table("LAZ decode (site_20M.laz)", ["tool", "points", "seconds", "M points/s", "liftplan speed-up"],
          lambda r: r["op"] == "decode",
          lambda r: [r["tool"], f"{r['points']:,}", f"{r['seconds']:.2f}", f"{r['points_per_s'] / 1e6:.2f}",
                     f"{r['seconds'] / lp[('decode', r['points'], None)]['seconds']:.2f}x"])
    table("Voxel-centroid thinning, 0.05 m, points already in memory",
          ["tool", "points", "voxels", "seconds", "liftplan speed-up"],
          lambda r: r["op"] == "voxel",
          lambda r: [r["tool"], f"{r['points']:,}", f"{r.get('voxels', 0):,}", f"{r['seconds']:.2f}",
                     f"{r['seconds'] / lp[('voxel', r['points'], None)]['seconds']:.2f}x"])
    table("Point-to-plane ICP, scan-2 onto scan-1 (5 cm thinned, about 100 k points each)",
          ["tool", "start", "normals s", "ICP s", "rotation error deg", "translation error mm",
           "ICP time vs liftplan"],
          lambda r: r["op"] == "icp",
          lambda r: [r["tool"], r["start"], f"{r['normals_seconds']:.2f}", f"{r['icp_seconds']:.2f}",
                     f"{r['rotation_error_deg']:.4f}", f"{r['translation_error_mm']:.1f}",
                     f"{r['icp_seconds'] / lp[('icp', r['source_points'], r['start'])]['icp_seconds']:.2f}x"])
    table("Peak memory thinning 100 M points (site_100M_stacked.laz, 0.05 m)", ["tool", "peak RSS MB", "seconds"],
          lambda r: r["op"] == "memory_100M",
          lambda r: [r["tool"], f"{r['peak_rss_mb']:,}", f"{r['seconds']:.1f}"])
    print("\n".join(out))


def main():
    op = sys.argv[1]
    if op == "decode":
        rows = decode(sys.argv[2])
    elif op == "voxel":
        rows = voxel(sys.argv[2], float(sys.argv[3]))
    elif op == "icp":
        rows = icp(sys.argv[2])
    elif op == "pdal":
        rows = pdal(sys.argv[2], float(sys.argv[3]))
    elif op == "summary":
        summary(sys.argv[2])
        return
    else:
        sys.exit("usage: bench_scans_peers.py decode FILE | voxel FILE EDGE | icp DIR | pdal FILE EDGE | summary RESULTS")
    for row in rows:
        print(json.dumps(row))


if __name__ == "__main__":
    main()
