//! Reading Gmsh MSH 4.1 files (ASCII and binary) through the `mshio` crate.
//!
//! Format reference: Gmsh reference manual, section "MSH file format" (version 4.1),
//! <https://gmsh.info/doc/texinfo/gmsh.html#MSH-file-format>. Physical groups are attached to
//! geometrical entities in `$Entities`; their names are in `$PhysicalNames`.

mod header;

use std::collections::{BTreeMap, HashMap};
use std::path::Path;

use mshio::{ElementType, MshFile, MshParserError};

use crate::error::{MeshError, MeshErrorKind};
use crate::mesh::{is_degenerate, Mesh, Region};

/// A `|z|` larger than this factor times the diameter of the triangles' nodes is not planar.
const PLANARITY: f64 = 1e-9;

/// Reads a Gmsh MSH 4.1 file (ASCII or binary) into a [`Mesh`].
///
/// - 3-node triangles (element type 2) of each 2D physical group form a region named from
///   `$PhysicalNames` (`region_<tag>` when unnamed), regions ordered by physical tag; a file
///   without any physical group gives one region `domain` (tag 0) of all its triangles.
/// - 2-node lines (type 1) of each 1D physical group form an edge set (and the node set of
///   the same name), named `line_<tag>` when unnamed; points (type 15) of each 0D physical
///   group form a node set, `point_<tag>` when unnamed. Groups of the same dimension and
///   name are merged.
/// - Nodes are the nodes of the triangles, numbered in increasing Gmsh tag order; other
///   nodes are dropped.
///
/// Errors name the file, the place (line or byte, section, element or node tag) and the
/// reason: unreadable file, a version other than 4.1 (2.2: convert with
/// `gmsh -format msh41`), a truncated or corrupt file, an element other than a 3-node
/// triangle in a surface ("only 3-node triangles are supported"), a line or point whose
/// nodes are not nodes of the triangles, a z coordinate that is not (near) zero, 3D
/// elements, a degenerate triangle, an edge shared by three triangles.
pub fn read_msh(path: &Path) -> Result<Mesh, MeshError> {
    let origin = path.display().to_string();
    let bytes = std::fs::read(path)
        .map_err(|e| MeshError::new(MeshErrorKind::Io, &origin, format!("cannot read: {e}")))?;
    parse_msh(&bytes, &origin)
}

/// Parses the bytes of a MSH 4.1 file as [`read_msh`] does; `origin` names the source in
/// errors (usually its path).
pub fn parse_msh(bytes: &[u8], origin: &str) -> Result<Mesh, MeshError> {
    let header = header::check_header(bytes, origin)?;
    let names = header::physical_names(bytes, origin)?;
    let parsed = std::panic::catch_unwind(|| {
        mshio::parse_msh_bytes(bytes).map_err(|e| translate(&e, bytes, origin, header.binary))
    });
    let msh = match parsed {
        Ok(result) => result?,
        Err(_) => {
            return Err(MeshError::new(
                MeshErrorKind::Format,
                origin,
                "the MSH parser (mshio) stopped on malformed content",
            ))
        }
    };
    convert(&msh, &names, origin)
}

/// Checks the counts and tag ranges the `$Nodes` and `$Elements` headers state against the
/// blocks that follow: a file whose header disagrees with its content is damaged or cut.
fn header_counts(msh: &MshFile<u64, i32, f64>) -> Result<(), (String, String)> {
    if let Some(nodes) = &msh.data.nodes {
        let held: usize = nodes.node_blocks.iter().map(|b| b.nodes.len()).sum();
        if held as u64 != nodes.num_nodes {
            return Err((
                "$Nodes".into(),
                format!(
                    "the header says {} nodes, the blocks hold {held}",
                    nodes.num_nodes
                ),
            ));
        }
        let tags = (nodes.node_blocks.iter())
            .filter_map(|b| b.node_tags.as_ref())
            .flat_map(|map| map.keys().copied());
        let range = nodes.min_node_tag..=nodes.max_node_tag;
        if let Some(t) = tags.into_iter().find(|t| !range.contains(t)) {
            return Err((
                format!("$Nodes, node {t}"),
                format!("outside the tag range {range:?} the header states"),
            ));
        }
        let dense = nodes.node_blocks.iter().all(|b| b.node_tags.is_none());
        if dense && held > 0 && nodes.max_node_tag - nodes.min_node_tag + 1 != held as u64 {
            return Err((
                "$Nodes".into(),
                format!(
                    "the header's tags {range:?} do not number the {held} nodes the blocks hold"
                ),
            ));
        }
    }
    if let Some(elements) = &msh.data.elements {
        let held: usize = (elements.element_blocks.iter())
            .map(|b| b.elements.len())
            .sum();
        if held as u64 != elements.num_elements {
            return Err((
                "$Elements".into(),
                format!(
                    "the header says {} elements, the blocks hold {held}",
                    elements.num_elements
                ),
            ));
        }
    }
    Ok(())
}

/// A mshio error as a [`MeshError`]: the innermost error, the sections it was met in, and
/// its line (ASCII) or byte offset (binary).
fn translate(err: &MshParserError<&[u8]>, bytes: &[u8], origin: &str, binary: bool) -> MeshError {
    let trace = err.filtered_backtrace();
    let Some((rest, _)) = trace.first() else {
        return MeshError::new(
            MeshErrorKind::Format,
            origin,
            "malformed or truncated content (the MSH parser gave no detail)",
        );
    };
    let offset = bytes.len().saturating_sub(rest.len());
    let what = (trace.iter())
        .find(|(_, k)| k.context().is_none())
        .map_or_else(|| "malformed content".to_string(), |(_, k)| k.to_string());
    let within: Vec<&str> = (trace.iter().rev())
        .filter_map(|(_, k)| k.context())
        .collect();
    let mut reason = what;
    if !within.is_empty() {
        reason = format!("{reason} (in {})", within.join(" > "));
    }
    let last_line = bytes.trim_ascii_end().rsplit(|&b| b == b'\n').next();
    if !last_line.is_some_and(|l| l.trim_ascii().starts_with(b"$End")) {
        reason = format!("{reason}; the file does not end with an $End line (truncated?)");
    }
    MeshError::new(MeshErrorKind::Format, origin, reason)
        .at(header::place_of(bytes, offset, binary))
}

/// Physical groups of one dimension: physical tag -> members.
type Groups<T> = BTreeMap<i32, Vec<T>>;

fn convert(
    msh: &MshFile<u64, i32, f64>,
    names: &HashMap<(i32, i32), String>,
    origin: &str,
) -> Result<Mesh, MeshError> {
    let err = |kind, place: String, reason: String| MeshError::new(kind, origin, reason).at(place);
    // Physical tags of each entity, keyed by (dimension, entity tag).
    let mut physical: HashMap<(i32, i32), &[i32]> = HashMap::new();
    if let Some(e) = &msh.data.entities {
        physical.extend(e.points.iter().map(|p| ((0, p.tag), &p.physical_tags[..])));
        physical.extend(e.curves.iter().map(|c| ((1, c.tag), &c.physical_tags[..])));
        physical.extend(
            e.surfaces
                .iter()
                .map(|s| ((2, s.tag), &s.physical_tags[..])),
        );
        physical.extend(e.volumes.iter().map(|v| ((3, v.tag), &v.physical_tags[..])));
    }
    let has_groups = physical.values().any(|p| !p.is_empty());

    header_counts(msh).map_err(|(place, reason)| err(MeshErrorKind::Format, place, reason))?;
    // Node tag -> coordinates.
    let mut coords: HashMap<u64, [f64; 3]> = HashMap::new();
    if let Some(nodes) = &msh.data.nodes {
        let mut next_tag = nodes.min_node_tag;
        for block in &nodes.node_blocks {
            let mut tags = vec![0u64; block.nodes.len()];
            match &block.node_tags {
                Some(map) => map.iter().for_each(|(&tag, &i)| tags[i] = tag),
                // mshio keeps the tags of a sparse section only; a dense one holds the tags
                // min..=max, which Gmsh writes in increasing order across the blocks.
                None => tags.iter_mut().for_each(|t| {
                    *t = next_tag;
                    next_tag += 1;
                }),
            }
            for (tag, n) in tags.into_iter().zip(&block.nodes) {
                if coords.insert(tag, [n.x, n.y, n.z]).is_some() {
                    return Err(err(
                        MeshErrorKind::Format,
                        format!("$Nodes, node {tag}"),
                        "node tag defined twice".into(),
                    ));
                }
            }
        }
    }

    // Triangles (node tags) with their element tag and 2D group; lines and points per group.
    let mut triangles: Vec<([u64; 3], u64, i32)> = Vec::new();
    let mut lines: Groups<([u64; 2], u64)> = BTreeMap::new();
    let mut points: Groups<(u64, u64)> = BTreeMap::new();
    let empty: &[i32] = &[];
    // Surfaces first, so that a second-order mesh is reported at its triangles.
    let mut blocks: Vec<_> = msh
        .data
        .elements
        .iter()
        .flat_map(|e| &e.element_blocks)
        .collect();
    blocks.sort_by_key(|b| std::cmp::Reverse(b.entity_dim));
    for block in blocks {
        let (dim, entity) = (block.entity_dim, block.entity_tag);
        let groups = physical.get(&(dim, entity)).copied().unwrap_or(empty);
        let Some(first) = block.elements.first() else {
            continue;
        };
        let place = format!(
            "$Elements, element {} (entity {entity} of dimension {dim})",
            first.element_tag
        );
        match dim {
            2 => {
                if block.element_type != ElementType::Tri3 {
                    return Err(err(
                        MeshErrorKind::Unsupported,
                        place,
                        format!(
                            "only 3-node triangles are supported, found {:?} elements",
                            block.element_type
                        ),
                    ));
                }
                let group = match (has_groups, groups) {
                    (false, _) => 0,
                    (true, [g]) => *g,
                    (true, []) => {
                        return Err(err(
                            MeshErrorKind::Unsupported,
                            place,
                            "these triangles belong to no 2D physical group while other surfaces do: \
                             add the surface to a physical group"
                                .into(),
                        ))
                    }
                    (true, many) => {
                        return Err(err(
                            MeshErrorKind::Unsupported,
                            place,
                            format!("the surface belongs to several 2D physical groups {many:?}: a triangle needs one region"),
                        ))
                    }
                };
                for e in &block.elements {
                    let n = &e.nodes;
                    triangles.push(([n[0], n[1], n[2]], e.element_tag, group));
                }
            }
            1 if !groups.is_empty() => {
                if block.element_type != ElementType::Lin2 {
                    return Err(err(
                        MeshErrorKind::Unsupported,
                        place,
                        format!("only 2-node lines are supported in 1D physical groups, found {:?} elements", block.element_type),
                    ));
                }
                for &g in groups {
                    let set = lines.entry(g).or_default();
                    set.extend(
                        block
                            .elements
                            .iter()
                            .map(|e| ([e.nodes[0], e.nodes[1]], e.element_tag)),
                    );
                }
            }
            0 if !groups.is_empty() => {
                for &g in groups {
                    let set = points.entry(g).or_default();
                    set.extend(block.elements.iter().map(|e| (e.nodes[0], e.element_tag)));
                }
            }
            3 => return Err(err(
                MeshErrorKind::Unsupported,
                place,
                "3D elements are not supported: the mesh must be 2D (triangles in the plane z = 0)"
                    .into(),
            )),
            _ => {}
        }
    }
    if triangles.is_empty() {
        return Err(MeshError::new(
            MeshErrorKind::Format,
            origin,
            "no triangles (element type 2) in the file",
        ));
    }

    // Compact the nodes of the triangles, in increasing tag order.
    let mut used: Vec<u64> = triangles.iter().flat_map(|t| t.0).collect();
    used.sort_unstable();
    used.dedup();
    let mut index: HashMap<u64, u32> = HashMap::with_capacity(used.len());
    let mut nodes = Vec::with_capacity(used.len());
    for (i, &tag) in used.iter().enumerate() {
        let Some(&p) = coords.get(&tag) else {
            let t = triangles
                .iter()
                .find(|t| t.0.contains(&tag))
                .map_or(0, |t| t.1);
            return Err(err(
                MeshErrorKind::Format,
                format!("$Elements, element {t}"),
                format!("node {tag} is not in the $Nodes section"),
            ));
        };
        index.insert(tag, i as u32);
        nodes.push(p);
    }
    check_coordinates(&nodes, &used, origin)?;

    // Regions ordered by physical tag.
    let mut group_tags: Vec<i32> = triangles.iter().map(|t| t.2).collect();
    group_tags.sort_unstable();
    group_tags.dedup();
    let regions: Vec<Region> = if has_groups {
        group_tags
            .iter()
            .map(|&tag| Region {
                name: names
                    .get(&(2, tag))
                    .cloned()
                    .unwrap_or_else(|| format!("region_{tag}")),
                tag,
            })
            .collect()
    } else {
        vec![Region {
            name: "domain".into(),
            tag: 0,
        }]
    };
    for (i, r) in regions.iter().enumerate() {
        if regions[..i].iter().any(|q| q.name == r.name) {
            return Err(err(
                MeshErrorKind::Unsupported,
                "$PhysicalNames".into(),
                format!("two 2D physical groups are both named `{}`", r.name),
            ));
        }
    }
    let xy: Vec<[f64; 2]> = nodes.iter().map(|p| [p[0], p[1]]).collect();
    let mut tris = Vec::with_capacity(triangles.len());
    let mut triangle_region = Vec::with_capacity(triangles.len());
    for (tags, element, group) in &triangles {
        let t = tags.map(|n| index[&n]);
        let [a, b, c] = t.map(|n| xy[n as usize]);
        if is_degenerate(a, b, c) {
            return Err(err(
                MeshErrorKind::Invalid,
                format!("$Elements, element {element}"),
                format!("degenerate triangle (zero area), nodes {tags:?}"),
            ));
        }
        tris.push(t);
        let r = if has_groups {
            group_tags.binary_search(group).unwrap_or(0)
        } else {
            0
        };
        triangle_region.push(r as u32);
    }
    let mut mesh =
        Mesh::new(xy, tris, triangle_region, regions).map_err(|e| e.from_origin(origin))?;

    // Edge sets, then node sets of points, merged by name.
    let node_of = |tag: u64, element: u64, what: &str| {
        index.get(&tag).copied().ok_or_else(|| {
            err(
                MeshErrorKind::Invalid,
                format!("$Elements, element {element}"),
                format!("{what} uses node {tag}, which is not a node of any triangle"),
            )
        })
    };
    let mut edge_sets: BTreeMap<String, Vec<[u32; 2]>> = BTreeMap::new();
    for (tag, members) in &lines {
        let name = names
            .get(&(1, *tag))
            .cloned()
            .unwrap_or_else(|| format!("line_{tag}"));
        let set = edge_sets.entry(name).or_default();
        for (pair, element) in members {
            let what = format!("a line of physical group {tag}");
            set.push([
                node_of(pair[0], *element, &what)?,
                node_of(pair[1], *element, &what)?,
            ]);
        }
    }
    for (name, edges) in &edge_sets {
        mesh = mesh
            .with_edge_set(name, edges)
            .map_err(|e| e.from_origin(origin))?;
    }
    for (tag, members) in &points {
        let name = names
            .get(&(0, *tag))
            .cloned()
            .unwrap_or_else(|| format!("point_{tag}"));
        let what = format!("a point of physical group {tag}");
        let set: Vec<u32> = members
            .iter()
            .map(|(n, element)| node_of(*n, *element, &what))
            .collect::<Result<_, _>>()?;
        mesh = mesh
            .with_node_set(&name, &set)
            .map_err(|e| e.from_origin(origin))?;
    }
    Ok(mesh)
}

/// Rejects non-finite coordinates and nodes whose z is not (near) zero:
/// `|z| <= PLANARITY * diameter`.
fn check_coordinates(nodes: &[[f64; 3]], tags: &[u64], origin: &str) -> Result<(), MeshError> {
    if let Some(i) = nodes.iter().position(|p| p.iter().any(|v| !v.is_finite())) {
        return Err(MeshError::new(
            MeshErrorKind::Invalid,
            origin,
            format!("non-finite coordinate {:?}", nodes[i]),
        )
        .at(format!("$Nodes, node {}", tags[i])));
    }
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for p in nodes {
        for k in 0..2 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let diameter = ((hi[0] - lo[0]).powi(2) + (hi[1] - lo[1]).powi(2)).sqrt();
    match nodes.iter().position(|p| p[2].abs() > PLANARITY * diameter) {
        Some(i) => Err(MeshError::new(
            MeshErrorKind::Unsupported,
            origin,
            format!(
                "z = {} is not zero: only planar meshes in the plane z = 0 are supported",
                nodes[i][2]
            ),
        )
        .at(format!("$Nodes, node {}", tags[i]))),
        None => Ok(()),
    }
}
