//! A small glTF 2.0 writer for the tests: triangle meshes (positions, optional uvs, u32
//! indices) in one buffer, with nodes, materials, lights, cameras and images given as JSON,
//! written as `.gltf` + `.bin` or as `.glb`.
#![allow(dead_code)]

use std::path::{Path, PathBuf};

use serde_json::{Value, json};

pub struct Gltf {
    pub json: Value,
    pub bin: Vec<u8>,
}

impl Default for Gltf {
    fn default() -> Self {
        Self::new()
    }
}

impl Gltf {
    pub fn new() -> Gltf {
        Gltf {
            json: json!({
                "asset": { "version": "2.0", "generator": "brume tests" },
                "scene": 0,
                "scenes": [ { "nodes": [] } ],
                "nodes": [], "meshes": [], "accessors": [], "bufferViews": [],
                "buffers": [], "materials": [],
            }),
            bin: Vec::new(),
        }
    }

    fn push(&mut self, array: &str, v: Value) -> usize {
        let a = self.json[array].as_array_mut().expect("array");
        a.push(v);
        a.len() - 1
    }

    /// A buffer view over `bytes`, 4-byte aligned.
    pub fn view(&mut self, bytes: &[u8]) -> usize {
        while !self.bin.len().is_multiple_of(4) {
            self.bin.push(0);
        }
        let offset = self.bin.len();
        self.bin.extend_from_slice(bytes);
        self.push(
            "bufferViews",
            json!({ "buffer": 0, "byteOffset": offset, "byteLength": bytes.len() }),
        )
    }

    fn floats(&mut self, v: &[f32], ty: &str, n: usize) -> usize {
        let bytes: Vec<u8> = v.iter().flat_map(|x| x.to_le_bytes()).collect();
        let view = self.view(&bytes);
        let mut acc = json!({
            "bufferView": view, "componentType": 5126, "count": v.len() / n, "type": ty,
        });
        if ty == "VEC3" {
            let (mut lo, mut hi) = ([f32::MAX; 3], [f32::MIN; 3]);
            for p in v.chunks_exact(3) {
                for k in 0..3 {
                    lo[k] = lo[k].min(p[k]);
                    hi[k] = hi[k].max(p[k]);
                }
            }
            acc["min"] = json!(lo);
            acc["max"] = json!(hi);
        }
        self.push("accessors", acc)
    }

    /// A mesh of one triangle primitive; returns the mesh index.
    pub fn mesh(
        &mut self,
        positions: &[[f32; 3]],
        uvs: Option<&[[f32; 2]]>,
        indices: &[u32],
        material: Option<usize>,
    ) -> usize {
        let flat: Vec<f32> = positions.iter().flatten().copied().collect();
        let pos = self.floats(&flat, "VEC3", 3);
        let mut attributes = json!({ "POSITION": pos });
        if let Some(uv) = uvs {
            let flat: Vec<f32> = uv.iter().flatten().copied().collect();
            attributes["TEXCOORD_0"] = json!(self.floats(&flat, "VEC2", 2));
        }
        let bytes: Vec<u8> = indices.iter().flat_map(|i| i.to_le_bytes()).collect();
        let view = self.view(&bytes);
        let idx = self.push(
            "accessors",
            json!({ "bufferView": view, "componentType": 5125, "count": indices.len(),
                    "type": "SCALAR" }),
        );
        let mut prim = json!({ "attributes": attributes, "indices": idx, "mode": 4 });
        if let Some(m) = material {
            prim["material"] = json!(m);
        }
        self.push("meshes", json!({ "primitives": [prim] }))
    }

    /// A node (as JSON), placed at the scene's root; returns its index.
    pub fn node(&mut self, node: Value) -> usize {
        let i = self.push("nodes", node);
        self.json["scenes"][0]["nodes"]
            .as_array_mut()
            .expect("scene nodes")
            .push(json!(i));
        i
    }

    pub fn material(&mut self, m: Value) -> usize {
        self.push("materials", m)
    }

    /// A `KHR_lights_punctual` light; returns its index.
    pub fn light(&mut self, l: Value) -> usize {
        self.use_extension("KHR_lights_punctual");
        let ext = self.json["extensions"]["KHR_lights_punctual"]["lights"].take();
        let mut lights = ext.as_array().cloned().unwrap_or_default();
        lights.push(l);
        let n = lights.len() - 1;
        self.json["extensions"]["KHR_lights_punctual"]["lights"] = Value::Array(lights);
        n
    }

    pub fn camera(&mut self, c: Value) -> usize {
        if self.json.get("cameras").is_none() {
            self.json["cameras"] = json!([]);
        }
        self.push("cameras", c)
    }

    pub fn use_extension(&mut self, name: &str) {
        if self.json.get("extensionsUsed").is_none() {
            self.json["extensionsUsed"] = json!([]);
        }
        let used = self.json["extensionsUsed"].as_array_mut().expect("array");
        if !used.iter().any(|u| u == name) {
            used.push(json!(name));
        }
    }

    /// An image stored in the buffer, with a texture of it; returns the texture index.
    pub fn texture(&mut self, bytes: &[u8], mime: &str) -> usize {
        let view = self.view(bytes);
        for k in ["images", "textures"] {
            if self.json.get(k).is_none() {
                self.json[k] = json!([]);
            }
        }
        let image = self.push("images", json!({ "bufferView": view, "mimeType": mime }));
        self.push("textures", json!({ "source": image }))
    }

    /// `dir/name.gltf` with its buffer in `dir/name.bin`.
    pub fn write_gltf(&self, dir: &Path, name: &str) -> PathBuf {
        let mut json = self.json.clone();
        let bin = format!("{name}.bin");
        json["buffers"] = json!([{ "uri": bin, "byteLength": self.bin.len() }]);
        std::fs::write(dir.join(&bin), &self.bin).expect("write bin");
        let path = dir.join(format!("{name}.gltf"));
        std::fs::write(&path, serde_json::to_vec_pretty(&json).expect("json")).expect("write");
        path
    }

    /// `path` as a binary glTF (GLB) with the buffer in its BIN chunk.
    pub fn write_glb(&self, path: &Path) {
        let mut json = self.json.clone();
        json["buffers"] = json!([{ "byteLength": self.bin.len() }]);
        let mut text = serde_json::to_vec(&json).expect("json");
        while !text.len().is_multiple_of(4) {
            text.push(b' ');
        }
        let mut bin = self.bin.clone();
        while !bin.len().is_multiple_of(4) {
            bin.push(0);
        }
        let total = 12 + 8 + text.len() + 8 + bin.len();
        let mut out = Vec::with_capacity(total);
        out.extend_from_slice(b"glTF");
        out.extend_from_slice(&2u32.to_le_bytes());
        out.extend_from_slice(&(total as u32).to_le_bytes());
        out.extend_from_slice(&(text.len() as u32).to_le_bytes());
        out.extend_from_slice(b"JSON");
        out.extend_from_slice(&text);
        out.extend_from_slice(&(bin.len() as u32).to_le_bytes());
        out.extend_from_slice(b"BIN\0");
        out.extend_from_slice(&bin);
        std::fs::write(path, out).expect("write glb");
    }
}
