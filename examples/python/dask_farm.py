"""One image on many machines with Dask distributed: pass ranges mapped over the workers,
the parts merged into exactly the image one process renders (docs/distributed.md).

    python examples/python/dask_farm.py SCENE --passes 40 --parts 8 -o out.exr \
        [--scheduler tcp://host:8786]       # default: a LocalCluster on this machine

Each task renders passes A..B of the seed's sequence (`Scene.render(pass_range=(A, B))`) and
writes its film part to a folder every worker can reach; the client merges the parts with
`brume.merge`. A task that fails is simply run again by Dask: its part is the same bits.
"""

import argparse
from pathlib import Path


def ranges(passes, parts):
    """`parts` adjacent pass ranges covering 0..passes, as even as possible."""
    edges = [round(i * passes / parts) for i in range(parts + 1)]
    return [(a, b) for a, b in zip(edges, edges[1:]) if b > a]


def render_part(scene, sets, seed, pass_range, folder):
    """A Dask task: renders one pass range and writes its film part; returns the part's path."""
    import brume

    a, b = pass_range
    part = Path(folder) / f"part-{a}-{b}.brume"
    brume.load(scene, set=sets).render(pass_range=(a, b), seed=seed, progress=False).save(part)
    return str(part)


def render_on_dask(client, scene, passes, parts, folder, seed=0, sets=None):
    """Renders `passes` passes of `scene` as `parts` tasks on `client`'s workers and merges
    them; returns the merged `brume.RenderResult`."""
    import brume

    futures = [client.submit(render_part, str(scene), sets or {}, seed, r, str(folder), pure=False)
               for r in ranges(passes, parts)]
    return brume.merge(client.gather(futures))


def main():
    from dask.distributed import Client, LocalCluster

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("scene", type=Path)
    ap.add_argument("--passes", type=int, required=True)
    ap.add_argument("--parts", type=int, default=8)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--scheduler", help="address of a Dask scheduler (default: a LocalCluster)")
    ap.add_argument("--parts-folder", type=Path, default=Path("parts"))
    ap.add_argument("-o", "--output", type=Path, action="append", required=True)
    args = ap.parse_args()
    args.parts_folder.mkdir(parents=True, exist_ok=True)
    if args.scheduler:
        client = Client(args.scheduler)
    else:
        client = Client(LocalCluster(n_workers=2, threads_per_worker=1))
    with client:
        result = render_on_dask(client, args.scene.resolve(), args.passes, args.parts,
                                args.parts_folder.resolve(), seed=args.seed)
    for out in args.output:
        result.save(out)
    print(f"merged {result.passes} passes; wrote {', '.join(map(str, args.output))}")


if __name__ == "__main__":
    main()
