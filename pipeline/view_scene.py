"""`make view`: the liver of the haptic experiments in a browser, in one command.

Meshes the liver as the haptic experiments do (experiments/haptic_whole.json: SOFA's liver2
surface through Gmsh, 8 cm target edge at the file's decimetre scale), fixes its far side (the
same half-space node set), writes the scene config (the experiment's liver scene, with a probe
that pushes) and starts `haptic_sim view` on it:
    /usr/bin/python3 -m pipeline.view_scene [--port 8080] [--host 127.0.0.1]
The mesh and the config are kept under build/view/ (the mesh is made once); the config is the one
`haptic_sim run` and `serve` read too (cpp/apps/haptic_sim.md)."""
import argparse
import json
import os
import subprocess
import sys

from pipeline.artifacts import read_artifact, write_artifact
from pipeline.paths import BUILD, ROOT, rel
from pipeline.stages.dhd_node_sets import MESH_SCHEMA, TOOL as NODE_SETS_TOOL, add_node_sets
from pipeline.stages.stability_common import tool_path

EXPERIMENT = ROOT / "experiments" / "haptic_whole.json"


def liver_stages():
    """The liver's mesher config, node sets and scene of the haptic experiment (one source)."""
    stages = json.loads(EXPERIMENT.read_text())["stages"]
    run = stages["liver_run"]
    return stages["liver_mesh"]["config"], stages["liver"]["config"]["sets"], run["config"], run["sweep"]["input"][0]


def make_scene(folder):
    mesher_cfg, sets, scene, press = liver_stages()
    folder.mkdir(parents=True, exist_ok=True)
    raw, mesh = folder / "liver_raw.json", folder / "liver.json"
    if not mesh.exists():
        (folder / "liver_mesher.json").write_text(json.dumps(mesher_cfg))
        subprocess.run([str(tool_path("mesher")), "--config", str(folder / "liver_mesher.json"), "--out", str(raw)],
                       cwd=ROOT, check=True)
        payload, _ = add_node_sets(read_artifact(raw, MESH_SCHEMA)["payload"], sets)
        write_artifact(mesh, MESH_SCHEMA, 1, NODE_SETS_TOOL, {"mesh": rel(raw), "sets": sets}, payload, inputs=[raw])
    # The pointer pushes (a tip off the surface touches nothing), so a hovering pointer costs the
    # frame nothing; the experiment's grasp holds the surface point it first touched.
    scene = dict(scene, model=dict(scene["model"], mesh=rel(mesh)), input=press,
                 probe=dict(scene["probe"], contact="push"))
    config = folder / "liver_scene.json"
    config.write_text(json.dumps(scene, indent=1))
    return config


def main(argv=None):
    parser = argparse.ArgumentParser(prog="make view", description=__doc__.splitlines()[0])
    parser.add_argument("--port", type=int, default=8080)
    parser.add_argument("--host", default="127.0.0.1")
    args = parser.parse_args(argv)
    config = make_scene(BUILD / "view")
    print(f"view: the liver scene is {rel(config)}; open http://{args.host}:{args.port}/ (Ctrl-C ends it)", flush=True)
    cmd = [str(tool_path("haptic_sim")), "view", "--config", rel(config), "--port", str(args.port)]
    if args.host != "127.0.0.1":
        cmd += ["--host", args.host]
    os.chdir(ROOT)
    os.execv(cmd[0], cmd)


if __name__ == "__main__":
    sys.exit(main())
