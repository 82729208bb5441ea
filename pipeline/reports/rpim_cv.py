"""Which cross-validated candidate a fitted model actually uses (002 §4.3: orders by CV), and
what CV settings a table was scored with. The `cv` stage scores every candidate and marks its
own choice; the fit stage chooses again, with its own settings, and its choice is the one the
model plays back. The tables mark the fit's choice, say where the two differ, and state the
settings of both, read from the artifacts."""


def used_by_fit(table: dict, candidate: dict, fit: dict) -> bool:
    """Whether `fit` (a marquardt_fit "fit" payload) uses `candidate` of a CV `table`."""
    if not fit:
        return False
    sel = (fit.get("selection") or {}).get(table["direction"])
    if sel is None:
        return False
    if table["relation"] == "force_to_loaded":
        return candidate.get("order") == sel["force_order"]
    comp = sel["components"].get(table["component"])
    if comp is None:
        return False
    if table["relation"] == "surface":
        return candidate.get("surface") == comp["surface"]
    if table["relation"] == "parameters":
        # Relation 3 is scored for the surface family of its table; the fit's order counts only
        # where the fit uses a surface of that family.
        return comp["surface"].get("model") == table["model"] and candidate.get("order") == comp["parameter_order"]
    return False


def disagreements(cv: dict, fit: dict) -> list:
    """[(relation, direction, component)] where the fit uses another candidate than the cv
    stage's own choice (a candidate of the table marked "chosen" that the fit does not use, or
    the reverse)."""
    out = []
    for t in cv["tables"]:
        for r in t["candidates"]:
            if bool(r.get("chosen")) != used_by_fit(t, r, fit):
                out.append((t["relation"], t["direction"], t["component"]))
                break
    return out


def describe_settings(settings: dict) -> str:
    """"5-fold (seed 1, one_se)" or "leave-one-out (…)" from a payload's settings.cv."""
    cv = settings.get("cv", {}) if settings else {}
    folds = cv.get("folds")
    head = "leave-one-out" if folds == 0 else f"{folds}-fold" if folds is not None else "k-fold (folds not recorded)"
    extra = ", ".join(f"{k} {cv[k]}" for k in ("seed", "selection") if k in cv)
    return head + (f" ({extra})" if extra else "")


def settings_note(cv: dict, fit: dict) -> str:
    """The caption sentence on the CV settings of the table and of the fit, and where the fit's
    choice differs from the table's own."""
    table = describe_settings(cv.get("settings"))
    text = f"Scores: {table} cross-validation."
    if fit:
        cv_set = (cv.get("settings") or {}).get("cv", {})
        fit_set = (fit.get("settings") or {}).get("cv", {})
        if cv_set == fit_set:
            text += " The fit chose its orders with the same settings."
        else:
            differ = [k for k in sorted(set(cv_set) | set(fit_set)) if cv_set.get(k) != fit_set.get(k)]
            text += (f" The fit chose its orders with other settings ({describe_settings(fit.get('settings'))}; "
                     f"differing: {', '.join(differ)}), so its choice need not be this table's.")
        off = disagreements(cv, fit)
        if off:
            text += (f" The fit uses another candidate than this table's own choice in {len(off)} of "
                     f"{len(cv['tables'])} tables.")
    return text
