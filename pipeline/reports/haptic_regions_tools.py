import numpy as np
def report(ctx):
    for st in ["cube_tool_whole","cube_tool_regions","liver_tool_whole","liver_tool_regions","cube_cut_whole","cube_cut_regions"]:
        for r in ctx.runs(st):
            p=r.payload
            f=np.array(p["force"])
            reg=p.get("regions") or {}
            print(st, "peak",np.linalg.norm(f,axis=1).max(), "last",f[-1], "mean ms",1e3*p["timing"]["frame_seconds_mean"], "events",len(p["events"]), "cuts",len(p["cuts"]))
            if reg:
                print("   radius",reg["radius"], "primary", reg["primary"], "covers",reg["tool_covers"],"late",reg["late_contacts"],"builds",reg["builds"], "topo", reg["topology"])
            if p["cuts"]: print("   cuts secs", [round(c["seconds"]*1e3,3) for c in p["cuts"]][:10], len(p["cuts"]))
            for e in p["events"][:3]: print("   ev",e)
