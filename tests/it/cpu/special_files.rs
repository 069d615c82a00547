//! Files that are not what their names say, met while they change: a folder swapped for a link
//! out of the model's folder while a map is read, FIFOs, folders, loops of links and devices
//! where a map or a preset should be. Each is refused in one line that says what it is; no byte
//! from outside the folder is read, and nothing waits on a FIFO.

use std::path::Path;
use std::sync::atomic::{AtomicBool, Ordering};

use ssdo::preset::Preset;
use ssdo::scene::files::ModelFolder;

/// The bytes inside the model's folder and the ones outside it, told apart by their content.
const INSIDE: &[u8] = b"inside the model's folder";
const OUTSIDE: &[u8] = b"OUTSIDE: a secret of another folder";

#[cfg(unix)]
#[test]
fn a_folder_swapped_for_a_link_while_a_map_is_read_never_gives_the_outside_file() {
    let root = tempfile::tempdir().unwrap();
    let (model, secret) = (root.path().join("m"), root.path().join("secret"));
    std::fs::create_dir_all(model.join("sub")).unwrap();
    std::fs::create_dir_all(&secret).unwrap();
    std::fs::write(model.join("sub/map.bin"), INSIDE).unwrap();
    std::fs::write(secret.join("map.bin"), OUTSIDE).unwrap();
    let folder = ModelFolder::of(&model.join("model.obj"));
    // Another process's work, here a thread's: the subfolder and a link to the secret folder
    // trade places as fast as the file system allows.
    let stop = AtomicBool::new(false);
    let (mut read, mut refused, mut outside) = (0, 0, 0);
    std::thread::scope(|s| {
        s.spawn(|| {
            let (sub, parked) = (model.join("sub"), model.join("sub.parked"));
            while !stop.load(Ordering::Relaxed) {
                std::fs::rename(&sub, &parked).unwrap();
                std::os::unix::fs::symlink(&secret, &sub).unwrap();
                std::fs::remove_file(&sub).unwrap();
                std::fs::rename(&parked, &sub).unwrap();
            }
        });
        let started = std::time::Instant::now();
        while started.elapsed() < std::time::Duration::from_secs(2) || read < 50 {
            match folder.read("sub/map.bin", 1 << 20) {
                Ok((_, bytes)) if bytes == OUTSIDE => outside += 1,
                Ok((_, bytes)) => {
                    assert_eq!(bytes, INSIDE);
                    read += 1;
                }
                Err(_) => refused += 1,
            }
            if started.elapsed() > std::time::Duration::from_secs(20) {
                break;
            }
        }
        stop.store(true, Ordering::Relaxed);
    });
    assert_eq!(outside, 0, "the file outside was read {outside} times ({read} inside, {refused} refused)");
    assert!(read > 0, "nothing was read ({refused} refused)");
}

/// An OBJ quad whose material's colour map is `map`, in `dir`.
fn quad_with_map(dir: &Path, name: &str, map: &str) -> std::path::PathBuf {
    let quad = "v 0 0 0\nv 1 0 0\nv 1 0 1\nv 0 0 1\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 1 0\n";
    std::fs::write(dir.join(format!("{name}.mtl")), format!("newmtl a\nmap_Kd {map}\n")).unwrap();
    let obj = dir.join(format!("{name}.obj"));
    std::fs::write(&obj, format!("mtllib {name}.mtl\n{quad}usemtl a\nf 1/1/1 4/4/1 3/3/1 2/2/1\n")).unwrap();
    obj
}

#[cfg(unix)]
#[test]
fn a_map_that_is_no_file_says_what_it_is_not_that_it_is_missing() {
    let root = tempfile::tempdir().unwrap();
    let dir = root.path();
    std::fs::create_dir(dir.join("folder.png")).unwrap();
    std::os::unix::fs::symlink("loop.png", dir.join("loop.png")).unwrap();
    std::os::unix::fs::symlink("/dev/zero", dir.join("zero.png")).unwrap();
    std::os::unix::fs::symlink("gone.png", dir.join("dangling.png")).unwrap();
    let mut cases = vec![
        ("folder.png", "is a folder, not a file"),
        ("loop.png", "a loop of links"),
        ("zero.png", "a link to /dev/zero, outside the model's folder"),
        ("dangling.png", "is a link to gone.png, which does not exist"),
        ("absent.png", "absent.png: not found"),
    ];
    let fifo = dir.join("fifo.png");
    if std::process::Command::new("mkfifo").arg(&fifo).status().is_ok_and(|s| s.success()) {
        cases.push(("fifo.png", "is a FIFO (a named pipe), not a regular file"));
    }
    for (i, (map, needle)) in cases.into_iter().enumerate() {
        let model = ssdo::scene::load_model_file(&quad_with_map(dir, &format!("q{i}"), map)).unwrap();
        let said = model.warnings.join(" | ");
        assert!(said.contains(map) && said.contains(needle), "{map}: {said}");
        assert!(map == "absent.png" || !said.contains("not found"), "{map}: {said}");
    }
}

#[cfg(unix)]
#[test]
fn a_preset_that_is_no_small_file_is_refused_before_it_is_read() {
    let dir = tempfile::tempdir().unwrap();
    let big = dir.path().join("big.json");
    std::fs::write(&big, vec![b' '; 100 << 10]).unwrap();
    let mut cases = vec![
        (Path::new("/dev/zero").to_path_buf(), "is a device, not a regular file"),
        (dir.path().to_path_buf(), "is a folder, not a file"),
        (big, "is 100 KiB; files over 64 KiB are refused"),
    ];
    let fifo = dir.path().join("fifo.json");
    if std::process::Command::new("mkfifo").arg(&fifo).status().is_ok_and(|s| s.success()) {
        cases.push((fifo.clone(), "is a FIFO (a named pipe), not a regular file"));
    }
    for (path, needle) in cases {
        if !path.exists() {
            continue;
        }
        // On a thread: a FIFO that blocked the read would hang the test, not fail it.
        let (sender, receiver) = std::sync::mpsc::channel();
        let shown = path.clone();
        std::thread::spawn(move || sender.send(Preset::load(&shown).map(|_| ()).unwrap_err().to_string()));
        let line = receiver
            .recv_timeout(std::time::Duration::from_secs(20))
            .unwrap_or_else(|_| panic!("{}: still reading after 20 s", path.display()));
        assert!(line.starts_with(&path.display().to_string()) && line.contains(needle), "{line}");
    }
    // A preset that is not UTF-8 says so.
    let latin = dir.path().join("latin.json");
    std::fs::write(&latin, b"{\"ssdo_preset\": 1, \"name\": \"caf\xe9\"}").unwrap();
    let line = Preset::load(&latin).unwrap_err().to_string();
    assert!(line.contains("not UTF-8"), "{line}");
}
