//! Mutated mesh files (deterministic byte flips, truncations, insertions) load
//! or fail with an error; none reaches a panic inside the parsers (the loader
//! would report that as "the parser failed").

mod common;

use common::{base64, f32_bytes, glb, u16_bytes, write};
use subcone_load::load_mesh_file;

struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
}

fn mutate(rng: &mut Rng, src: &[u8], interesting: &[u8]) -> Vec<u8> {
    let mut v = src.to_vec();
    for _ in 0..1 + rng.below(4) {
        match rng.below(6) {
            0 if !v.is_empty() => {
                let i = rng.below(v.len());
                v[i] ^= 1 << rng.below(8);
            }
            1 if !v.is_empty() => {
                let i = rng.below(v.len());
                v[i] = interesting[rng.below(interesting.len())];
            }
            2 => {
                let n = rng.below(v.len() + 1);
                v.truncate(n);
            }
            3 => {
                let i = rng.below(v.len() + 1);
                v.insert(i, interesting[rng.below(interesting.len())]);
            }
            4 if !v.is_empty() => {
                let a = rng.below(v.len());
                let b = (a + rng.below(16)).min(v.len());
                v.drain(a..b);
            }
            _ if v.len() >= 4 => {
                // Overwrite 4 bytes with an extreme u32 (lengths, counts, offsets).
                let i = rng.below(v.len() - 3);
                let x = [0u32, 1, 3, 0x7fff_ffff, 0xffff_ffff, 12, 19][rng.below(7)];
                v[i..i + 4].copy_from_slice(&x.to_le_bytes());
            }
            _ => {}
        }
    }
    v
}

fn quad() -> (Vec<u8>, String) {
    let positions = f32_bytes(&[0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 1.0, 0.0, 0.0, 1.0, 0.0]);
    let uvs = f32_bytes(&[0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0, 1.0]);
    let indices = u16_bytes(&[0, 1, 2, 0, 2, 3]);
    let mut buf = positions;
    buf.extend(&uvs);
    buf.extend(&indices);
    let json = r#"{"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],
"nodes":[{"mesh":0,"children":[1]},{"mesh":0,"translation":[0,0,1]}],
"meshes":[{"primitives":[{"attributes":{"POSITION":0,"TEXCOORD_0":1},"indices":2}]}],
"buffers":[{"byteLength":92}],
"bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":48},{"buffer":0,"byteOffset":48,"byteLength":32},{"buffer":0,"byteOffset":80,"byteLength":12}],
"accessors":[{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3","min":[0,0,0],"max":[1,1,0]},
{"bufferView":1,"componentType":5126,"count":4,"type":"VEC2"},
{"bufferView":2,"componentType":5123,"count":6,"type":"SCALAR"}]}"#;
    (buf, json.to_string())
}

/// Mutations per format: 400, or `$SUBCONE_MUTATIONS` for a longer local run.
fn rounds() -> usize {
    std::env::var("SUBCONE_MUTATIONS")
        .ok()
        .and_then(|n| n.parse().ok())
        .unwrap_or(400)
}

/// `src`, a valid `ext` file of `triangles` triangles written into `dir`,
/// loads; then [`rounds`] mutations of it (drawn from `seed`, inserting
/// `interesting` bytes) each load or fail with an error, never a panic
/// inside the parser.
fn survives_mutations(
    dir: &std::path::Path,
    ext: &str,
    src: &[u8],
    triangles: usize,
    seed: u64,
    interesting: &[u8],
) {
    let path = write(dir, &format!("ok.{ext}"), src);
    assert_eq!(load_mesh_file(&path).unwrap().0.len(), triangles);
    let mut rng = Rng(seed);
    for i in 0..rounds() {
        let path = write(
            dir,
            &format!("m{i}.{ext}"),
            mutate(&mut rng, src, interesting),
        );
        if let Err(e) = load_mesh_file(&path) {
            assert!(
                !e.to_string().contains("the parser failed"),
                "{}: {e}",
                path.display()
            );
        }
    }
}

#[test]
fn mutated_glb() {
    let dir = tempfile::tempdir().unwrap();
    let (buf, json) = quad();
    let src = glb(&json, &buf);
    survives_mutations(
        dir.path(),
        "glb",
        &src,
        4,
        0x9e37_79b9_7f4a_7c15,
        b"0123456789{}[]\",:-. ",
    );
}

#[test]
fn mutated_gltf_json() {
    let dir = tempfile::tempdir().unwrap();
    let (buf, json) = quad();
    let json = json.replace(
        r#"{"byteLength":92}"#,
        &format!(
            r#"{{"byteLength":92,"uri":"data:application/octet-stream;base64,{}"}}"#,
            base64(&buf)
        ),
    );
    survives_mutations(
        dir.path(),
        "gltf",
        json.as_bytes(),
        4,
        0x2545_f491_4f6c_dd1d,
        b"0123456789{}[]\",:-.e ",
    );
}

#[test]
fn mutated_obj() {
    let dir = tempfile::tempdir().unwrap();
    let src = "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\n\
               vn 0 0 1\nusemtl a\nf 1/1/1 2/2/1 3/3/1 4/1/1\nf -1 -2 -3\nl 1 2\n";
    write(dir.path(), "m.mtl", "newmtl a\nKd 0.5 0.2 0.1\nKe 0 0 0\n");
    survives_mutations(
        dir.path(),
        "obj",
        src.as_bytes(),
        3,
        0x5851_f42d_4c95_7f2d,
        b"0123456789/- \nfvne.#",
    );
}
