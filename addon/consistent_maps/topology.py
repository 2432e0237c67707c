"""Which meshes Compute takes, judged from their native reports (native.check_mesh dicts).

Two objects of equal genus 1 or more, or of genus 0 with Map the Pair Directly, are a pair mapped
onto each other directly (holes and loose vertices allowed: the report's 'pair_map_error'); any
other set needs meshes the sphere takes ('sphere_error'). No bpy here: the panel and Compute both
ask, so the panel lists exactly what Compute would refuse.
"""


def _has_handles(report):
    """One clean surface of genus >= 1, closed or with holes: mapped onto a partner directly."""
    return report["genus"] >= 1 and report["pair_map_error"] is None


def is_pair(reports, pair_map=False):
    """Whether the meshes are mapped onto each other directly rather than onto the sphere."""
    return len(reports) == 2 and (all(map(_has_handles, reports))
                                  or pair_map and all(r["genus"] == 0 for r in reports))


def _defect(name, error, report):
    hint = "" if report["manifold"] else " (Select > Select All by Trait > Non Manifold shows where)"
    return f"'{name}': {error}{hint}"


def problems(names, reports, pair_map=False):
    """Why Compute refuses these meshes (one name and report per object; empty when it takes them)."""
    if is_pair(reports, pair_map):
        found = [_defect(name, r["pair_map_error"], r) for name, r in zip(names, reports) if r["pair_map_error"]]
        if reports[0]["genus"] != reports[1]["genus"]:
            found.append(f"'{names[0]}' has genus {reports[0]['genus']} and '{names[1]}' genus {reports[1]['genus']}: "
                         f"objects with handles are mapped in pairs of equal genus")
        return found
    hint = " (two objects of equal genus can be mapped onto each other: make a set of just those two)"
    return [_defect(name, r["sphere_error"], r) + (hint if _has_handles(r) else "")
            for name, r in zip(names, reports) if r["sphere_error"]]
