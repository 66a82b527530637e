//! The stress report: the markdown table, and its copy into docs/stress.md.

use super::*;

/// The markdown table of a run: one row per case, one column group per sorter.
pub fn markdown(reports: &[CaseReport], size: u32) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "One row per case, figures summed over its views ({size}×{size} px). Per sorter: \
         order violations (oracle) / wrong unambiguous pixels against the z-buffer truth / \
         fragments beyond the pieces (BSP: the tree's; Newell: most cut in one frame) / \
         milliseconds (build + sorts); **bsp-merged** (split pieces drawn whole where nothing \
         between their fragments overlaps them): violations / wrong pixels / most items drawn \
         in one view / milliseconds. **px** unambiguous pixels judged per sorter; \
         **NaN, fb** non-finite coordinates in the exact sorters' draw lists and frames \
         where they gave up exactness. `auto` is the planner (in brackets what it ran: \
         `cull-only` on meshes in convex position); `centroid` is the inexact reference.\n"
    );
    let _ = writeln!(
        s,
        "| group | case | pieces | views | px | {} | NaN, fb | status |",
        SORTERS.join(" | ")
    );
    let _ = writeln!(
        s,
        "| --- | --- | ---: | ---: | ---: | {}---: | --- |",
        "---: | ".repeat(SORTERS.len())
    );
    for r in reports {
        let head = format!(
            "| {} | {} | {} | {} |",
            r.group,
            r.name,
            r.pieces,
            r.views.len()
        );
        if let Some(f) = &r.failure {
            let _ = writeln!(s, "{head} | | | | | | | **FAIL**: {f} |");
            continue;
        }
        if let Some(e) = &r.error {
            let _ = writeln!(s, "{head} | | | | | | | typed error: {e} |");
            continue;
        }
        let pixels = r.outcomes.first().map_or(0, |o| o.unambiguous_pixels);
        let cell = |name: &str| {
            r.outcomes
                .iter()
                .find(|o| o.sorter == name)
                .map_or_else(String::new, |o| match &o.panic {
                    Some(_) => "panic".to_owned(),
                    None if name == REFERENCE => format!("{} / {}", o.violations, o.wrong_pixels),
                    None if name == "bsp-merged" => format!(
                        "{} / {} / {} / {:.1}",
                        o.violations, o.wrong_pixels, o.drawn_max, o.ms
                    ),
                    None if name == "auto" => format!(
                        "{} / {} ({})",
                        o.violations,
                        o.wrong_pixels,
                        o.plan.as_deref().unwrap_or("?")
                    ),
                    None => format!(
                        "{} / {} / {} / {:.1}",
                        o.violations, o.wrong_pixels, o.fragments, o.ms
                    ),
                })
        };
        let exact = r.outcomes.iter().filter(|o| is_exact(&o.sorter));
        let (nan, fb) = exact.fold((0, 0), |(n, f), o| (n + o.non_finite, f + o.fallbacks));
        let problems = r.problems();
        let status = if problems.is_empty() {
            "ok".to_owned()
        } else if r.outcomes.iter().any(|o| o.panic.is_some()) {
            "**PANIC**".to_owned()
        } else {
            "**FAIL**".to_owned()
        };
        let cells = SORTERS.map(cell).join(" | ");
        let _ = writeln!(s, "{head} {pixels} | {cells} | {nan}, {fb} | {status} |");
    }
    s
}

pub(super) const BEGIN: &str = "<!-- stress:begin (cargo xtask stress --docs) -->";
pub(super) const END: &str = "<!-- stress:end -->";

pub(super) fn write_docs(table: &str, args: &StressArgs) -> Result<()> {
    let path = crate::workspace_root().join("docs/stress.md");
    let text =
        std::fs::read_to_string(&path).with_context(|| format!("reading {}", path.display()))?;
    let (Some(b), Some(e)) = (text.find(BEGIN), text.find(END)) else {
        bail!("{} has no markers {BEGIN} … {END}", path.display());
    };
    if e < b {
        bail!(
            "{}: the end marker comes before the begin marker",
            path.display()
        );
    }
    let mut command = "cargo xtask stress".to_owned();
    if args.quick {
        command.push_str(" --quick");
    }
    if args.size != 256 {
        let _ = write!(command, " --size {}", args.size);
    }
    let out = format!(
        "{}{BEGIN}\nCommand: `{command} --docs`.\n\n{table}\n{}",
        &text[..b],
        &text[e..]
    );
    std::fs::write(&path, out).with_context(|| format!("writing {}", path.display()))?;
    println!("wrote {}", path.display());
    Ok(())
}
