#!/usr/bin/env python3
"""Converts every mesh of a folder to an implicit surface, in parallel with Dask.

    python convert_dask.py MESH_DIR OUT_DIR [--resolution N] [--method iterative|normals]
                           [--workers K] [--scheduler ADDRESS]

Every mesh (.obj, .ply, .stl) of MESH_DIR becomes OUT_DIR/NAME.json (a model that rbfsurf.load
and the rbf command read; NAME is the mesh's file name, e.g. bunny.ply.json) and
OUT_DIR/NAME.report.json (the conversion's figures). The run is resumable: a mesh whose model
and report exist, made with the same method and resolution from the same file (size and
modification time), is skipped, so an interrupted run is simply run again. A mesh that fails
(a bad file, a worker that dies) is recorded in the summary (and in OUT_DIR/summary.json) and
does not stop the others; the exit code is 1 if any failed.

By default a LocalCluster of K worker processes runs on this machine. To use a cluster, start
a scheduler and workers where rbfsurf is installed (`dask scheduler`, then `dask worker
tcp://HOST:8786` on each machine, or dask-jobqueue / dask-kubernetes), give OUT_DIR on storage
that every worker sees, and pass --scheduler tcp://HOST:8786.
"""

import argparse
import json
import os
import sys
import time
from pathlib import Path

MESH_SUFFIXES = {".obj", ".ply", ".stl"}


def source_of(mesh_path, method, resolution):
    """What a model was made from: a finished one is reused only if this is unchanged."""
    st = mesh_path.stat()
    return {"method": method, "resolution": resolution, "mesh_bytes": st.st_size, "mesh_mtime_ns": st.st_mtime_ns}


def summary_row(row, report):
    return {**row, **{k: report.get(k) for k in ("centres", "seconds", "max_error_voxels", "rms_error_voxels")}}


def convert_one(mesh_path, out_dir, resolution, method):
    """Runs on a worker: one mesh to one model and one report; returns a summary row and
    never raises."""
    mesh_path, out_dir = Path(mesh_path), Path(out_dir)
    model_path = out_dir / f"{mesh_path.name}.json"
    report_path = out_dir / f"{mesh_path.name}.report.json"
    row = {"mesh": mesh_path.name, "model": model_path.name}
    try:
        import rbfsurf

        source = source_of(mesh_path, method, resolution)
        if model_path.exists() and report_path.exists():
            done = json.loads(report_path.read_text())
            if done.get("source") == source:
                return summary_row({**row, "status": "skipped"}, done)
        start = time.perf_counter()
        vertices, faces = rbfsurf.read_mesh(mesh_path)
        model, report = rbfsurf.convert(vertices, faces, method=method, resolution=resolution, return_report=True)
        report.update(
            mesh=mesh_path.name,
            source=source,
            vertices=len(vertices),
            faces=len(faces),
            centres=len(model.centres),
            seconds=round(time.perf_counter() - start, 3),
        )
        # Model first, report last, each written whole: a report means the mesh is done.
        model.save(model_path)
        tmp = report_path.with_name(f".{report_path.name}.{os.getpid()}.tmp")
        tmp.write_text(json.dumps(report, indent=1))
        os.replace(tmp, report_path)
        return summary_row({**row, "status": "done"}, report)
    except Exception as e:  # recorded, not fatal: the other meshes go on
        return {**row, "status": "failed", "error": f"{type(e).__name__}: {e}"}


def table(rows):
    """The summary as aligned text columns."""
    columns = ["mesh", "status", "centres", "max_error_voxels", "rms_error_voxels", "seconds", "error"]
    cells = [[("" if r.get(c) is None else f"{r[c]:.3g}" if isinstance(r.get(c), float) else str(r[c])) for c in columns] for r in rows]
    widths = [max(len(c), *(len(row[i]) for row in cells)) for i, c in enumerate(columns)]
    lines = ["  ".join(c.ljust(w) for c, w in zip(columns, widths))]
    lines += ["  ".join(v.ljust(w) for v, w in zip(row, widths)) for row in cells]
    return "\n".join(line.rstrip() for line in lines)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("mesh_dir", type=Path)
    parser.add_argument("out_dir", type=Path)
    parser.add_argument("--resolution", type=int, default=64, help="voxels along a mesh's longest side (iterative)")
    parser.add_argument("--method", choices=["iterative", "normals"], default="iterative")
    parser.add_argument("--workers", type=int, default=2, help="LocalCluster worker processes")
    parser.add_argument("--scheduler", help="address of a running Dask scheduler, e.g. tcp://host:8786")
    args = parser.parse_args(argv)

    meshes = sorted(p for p in args.mesh_dir.iterdir() if p.suffix.lower() in MESH_SUFFIXES)
    if not meshes:
        print(f"no .obj, .ply or .stl meshes in {args.mesh_dir}", file=sys.stderr)
        return 2
    args.out_dir.mkdir(parents=True, exist_ok=True)

    from dask.distributed import Client, LocalCluster, as_completed

    if args.scheduler:
        client = Client(args.scheduler)
        cluster = None
    else:
        import dask

        # Each worker's rbfsurf runs on its share of the cores, and a mesh that kills its
        # worker is reported at once instead of being retried on the others.
        os.environ.setdefault("RAYON_NUM_THREADS", str(max(1, (os.cpu_count() or 1) // args.workers)))
        dask.config.set({"distributed.scheduler.allowed-failures": 0})
        cluster = LocalCluster(n_workers=args.workers, threads_per_worker=1, dashboard_address=None)
        client = Client(cluster)
    rows = []
    try:
        futures = {
            client.submit(convert_one, str(m.resolve()), str(args.out_dir.resolve()), args.resolution, args.method, pure=False): m
            for m in meshes
        }
        for i, future in enumerate(as_completed(futures), 1):
            mesh = futures[future]
            try:
                row = future.result()
            except Exception as e:  # the worker died (memory, a crash): recorded, not fatal
                row = {"mesh": mesh.name, "model": f"{mesh.name}.json", "status": "failed", "error": f"{type(e).__name__}: {e}"}
            rows.append(row)
            print(f"[{i}/{len(meshes)}] {row['mesh']}: {row['status']}" + (f" ({row['error']})" if "error" in row else ""), flush=True)
    finally:
        client.close()
        if cluster is not None:
            cluster.close()

    rows.sort(key=lambda r: r["mesh"])
    (args.out_dir / "summary.json").write_text(json.dumps(rows, indent=1))
    print()
    print(table(rows))
    counts = {s: sum(r["status"] == s for r in rows) for s in ("done", "skipped", "failed")}
    print(f"\n{counts['done']} converted, {counts['skipped']} skipped (already done), {counts['failed']} failed")
    return 1 if counts["failed"] else 0


if __name__ == "__main__":
    sys.exit(main())
