//! Runs split into batches at the command line: `strahl render --batch I/N --partial FILE`
//! for every batch, then `strahl merge PARTS -o IMAGE`, writes the bytes one `strahl render`
//! writes; `strahl merge` refuses parts that do not make one run.

mod common;

use common::{strahl, temp};
use std::path::{Path, PathBuf};

/// The path-traced render every test splits (seed 0; `extra` arguments after the others).
fn render_args<'a>(extra: &[&'a str]) -> Vec<&'a str> {
    let mut args = vec![
        "render",
        "cornell",
        "--method",
        "pathtrace",
        "--width",
        "20",
        "--height",
        "14",
        "--spp",
        "11",
        "-q",
    ];
    args.extend_from_slice(extra);
    args
}

/// Runs `args`, which must succeed.
fn ok(args: &[&str]) {
    let run = strahl(args);
    assert!(
        run.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&run.stderr)
    );
}

/// Runs `args`, which must fail with a message containing `message`.
fn refused(args: &[&str], message: &str) {
    let run = strahl(args);
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(!run.status.success(), "{args:?} succeeded");
    assert!(stderr.contains(message), "{args:?}: {stderr}");
}

/// Batch `index` of `count` of the render (with `extra` arguments), written to a partial
/// file named `name`.
fn batch(index: u32, count: u32, name: &str, extra: &[&str]) -> PathBuf {
    let path = temp("batches", name);
    let which = format!("{index}/{count}");
    let mut args = render_args(&["--batch", &which, "--partial", path.to_str().unwrap()]);
    args.extend_from_slice(extra);
    ok(&args);
    path
}

fn text(path: &Path) -> &str {
    path.to_str().unwrap()
}

#[test]
fn merged_batches_write_the_single_render_byte_for_byte() {
    for format in ["pfm", "png"] {
        let single = temp("batches", &format!("single.{format}"));
        ok(&render_args(&["-o", text(&single)]));
        for count in [1, 3] {
            let parts: Vec<PathBuf> = (0..count)
                .map(|k| batch(k, count, &format!("part-{k}-of-{count}.json"), &[]))
                .collect();
            let merged = temp("batches", &format!("merged-{count}.{format}"));
            let mut args = vec!["merge", "-q", "-o", text(&merged)];
            args.extend(parts.iter().rev().map(|p| text(p)));
            ok(&args);
            assert_eq!(
                std::fs::read(&merged).unwrap(),
                std::fs::read(&single).unwrap(),
                "{count} batches, .{format}"
            );
        }
    }
}

#[test]
fn parts_that_do_not_make_one_render_are_refused() {
    let a = batch(0, 2, "a.json", &[]);
    let b = batch(1, 2, "b.json", &[]);
    let out = temp("batches", "refused.pfm");
    let merge = |parts: &[&Path]| {
        let mut args = vec!["merge", "-o", text(&out)];
        args.extend(parts.iter().map(|p| text(p)));
        args.iter().map(|s| s.to_string()).collect::<Vec<_>>()
    };
    let run = |parts: &[&Path], message: &str| {
        let args = merge(parts);
        refused(
            &args.iter().map(String::as_str).collect::<Vec<_>>(),
            message,
        );
    };
    run(&[&a], "batch 1/2 is missing");
    run(&[&a, &a, &b], "batch 0/2 is given twice");
    let other_seed = batch(1, 2, "seed.json", &["--seed", "5"]);
    run(&[&a, &other_seed], "batch 1/2 has other settings");
    let third = batch(1, 3, "third.json", &[]);
    run(&[&a, &third], "is not one of 2 batches");
    let other_scene = temp("batches", "other-scene.json");
    ok(&[
        "render",
        "cornell-textured",
        "--method",
        "pathtrace",
        "--width",
        "20",
        "--height",
        "14",
        "--spp",
        "11",
        "-q",
        "--batch",
        "1/2",
        "--partial",
        text(&other_scene),
    ]);
    run(
        &[&a, &other_scene],
        "a batch of scene 'cornell-textured', not of 'cornell'",
    );
    let light = temp("batches", "light.json");
    ok(&[
        "solve",
        "cornell",
        "--solver",
        "light-trace",
        "--photons",
        "1000",
        "-q",
        "--batch",
        "0/2",
        "--partial",
        text(&light),
    ]);
    run(&[&a, &light], "they do not merge");
    refused(&["merge", text(&a), text(&b)], "name the image with -o");
    refused(
        &["merge", "-o", text(&out), text(&light)],
        "name the report with --report",
    );
    let not_partial = temp("batches", "not-partial.json");
    std::fs::write(&not_partial, "{\"render\": 1}").unwrap();
    run(&[&not_partial], "not a partial result");
    assert!(!out.exists(), "no refused merge writes an image");
}

#[test]
fn methods_that_do_not_split_are_refused() {
    let part = temp("batches", "never.json");
    refused(
        &[
            "render",
            "cornell",
            "--method",
            "raytrace",
            "--batch",
            "0/2",
            "--partial",
            text(&part),
        ],
        "it needs --method pathtrace",
    );
    refused(
        &render_args(&[
            "--batch",
            "0/2",
            "--partial",
            text(&part),
            "--time-limit",
            "5",
        ]),
        "--time-limit with --batch",
    );
    refused(
        &render_args(&["--batch", "2/2", "--partial", text(&part)]),
        "is not a batch I/N",
    );
    assert!(!part.exists());
}
