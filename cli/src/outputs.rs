//! The files a run writes, checked before any work: no two outputs of one run name the same
//! file, none names the scene being read, and each can be written where it is named.

use anyhow::{Context, Result, bail};
use std::path::{Path, PathBuf};
use strahl::atomic_file::AtomicFile;

/// Refuses outputs (each with the flag that names it; `None` where not asked for) of which
/// two name one file, or one names the file `scene` (a scene path or a built-in name), or one
/// cannot be written where it is named ([`check_writable`]).
pub fn check(scene: &str, outputs: &[(&str, Option<&Path>)]) -> Result<()> {
    check_distinct(scene, outputs)?;
    for &(flag, path) in outputs {
        if let Some(path) = path {
            check_writable(flag, path)?;
        }
    }
    Ok(())
}

/// Refuses an output that cannot be written where it is named (a missing or read-only
/// folder, no permission, a folder in its place) by starting and abandoning the writing of
/// it — the temporary file beside it that `AtomicFile` begins with, removed at once — so that
/// the run fails before its work, not after. A device or other file that is not a regular
/// file (`/dev/full`, a pipe) is left to the writing itself: opening it may wait or succeed.
fn check_writable(flag: &str, path: &Path) -> Result<()> {
    if std::fs::metadata(path).is_ok_and(|m| !m.is_file() && !m.is_dir()) {
        return Ok(());
    }
    AtomicFile::create(path)
        .map(drop)
        .with_context(|| format!("{flag} {}: cannot write there", path.display()))
}

/// Refuses outputs of which two name one file, or one names the file `scene`.
fn check_distinct(scene: &str, outputs: &[(&str, Option<&Path>)]) -> Result<()> {
    let input = Path::new(scene);
    let input = input.is_file().then(|| identity(input));
    let named: Vec<(&str, &Path, PathBuf)> = outputs
        .iter()
        .filter_map(|&(flag, path)| path.map(|p| (flag, p, identity(p))))
        .collect();
    for (k, (flag, path, id)) in named.iter().enumerate() {
        if input.as_ref() == Some(id) {
            bail!(
                "{flag} {}: that is the scene being read; choose another file",
                path.display()
            );
        }
        if let Some((other, _, _)) = named[..k].iter().find(|(_, _, o)| o == id) {
            bail!(
                "{flag} {} names the file {other} writes too; choose another file",
                path.display()
            );
        }
    }
    Ok(())
}

/// The file `path` names, as far as it can be told before it exists: the canonical path of
/// the file, else of its folder joined with its name, else the path made absolute.
fn identity(path: &Path) -> PathBuf {
    if let Ok(canonical) = path.canonicalize() {
        return canonical;
    }
    let folder = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    };
    match (folder.canonicalize(), path.file_name()) {
        (Ok(folder), Some(name)) => folder.join(name),
        _ => std::path::absolute(path).unwrap_or_else(|_| path.to_path_buf()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_file_named_twice_is_refused_however_it_is_spelt() {
        let dir = std::env::temp_dir();
        let a = dir.join("strahl-outputs-a.png");
        let b = dir.join(".").join("strahl-outputs-a.png");
        let error = check_distinct("cornell", &[("-o", Some(&a)), ("--aa-map", Some(&b))])
            .unwrap_err()
            .to_string();
        assert!(
            error.contains("--aa-map") && error.contains("-o writes too"),
            "{error}"
        );
        let c = dir.join("strahl-outputs-c.png");
        check_distinct(
            "cornell",
            &[("-o", Some(&a)), ("--aa-map", Some(&c)), ("--export", None)],
        )
        .unwrap();
    }

    #[test]
    fn the_scene_being_read_is_not_an_output() {
        let scene = std::env::temp_dir().join("strahl-outputs-scene.toml");
        std::fs::write(&scene, "").unwrap();
        let error = check_distinct(scene.to_str().unwrap(), &[("--report", Some(&scene))])
            .unwrap_err()
            .to_string();
        assert!(error.contains("the scene being read"), "{error}");
        std::fs::remove_file(scene).unwrap();
    }
}
