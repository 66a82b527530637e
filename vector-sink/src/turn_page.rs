//! The page that turns with the pointer: a [`Presorted`]'s certified orders as data, and a
//! few lines of script that map the pointer to yaw and pitch, find the region of directions
//! holding the viewer, and show that region's order. The script orders nothing: every order
//! on the page was certified when the sorter was built.

use std::fmt::Write as _;
use std::sync::Arc;

use base64::Engine as _;
use face_sort::{
    CertifiedOrders, CertifiedOrdersError, Geometry, OrderStep, Presorted, Projection, View,
};
use glam::{DMat3, DMat4, DVec3};

use crate::Materials;
use crate::page_pieces::{Placement, num, piece_classes};

/// Options of [`write_turn_html`].
#[derive(Clone, Debug)]
#[non_exhaustive]
pub struct TurnPageOptions {
    /// Fill each face with its ID colour (CONVENTIONS.md) instead of `colour`. Default: false.
    pub ids: bool,
    /// Page background. Default: none: black in ID mode, white otherwise (as every page
    /// and the PNG).
    pub background: Option<[u8; 4]>,
    /// What fills each face in colour mode (a texture as its mean colour). Default: none
    /// (the palette).
    pub materials: Option<Arc<Materials>>,
    /// Each element is laid out at this many times its extent at rest (as
    /// [`SpinOptions::oversize`](crate::SpinOptions)). Default: 4.
    pub oversize: f64,
    /// Orthographic views get this perspective distance (pixels). Default: 1e8.
    pub orthographic_distance: f64,
    /// Views (yaw and pitch in degrees) the page turns through when it loads, the last shown
    /// until the pointer moves (a fragment `#yaw,pitch` in the page's address overrides
    /// them). Default: none, which shows yaw 0, pitch 0.
    pub start: Vec<(f64, f64)>,
}

impl TurnPageOptions {
    /// The defaults.
    pub const DEFAULT: TurnPageOptions = TurnPageOptions {
        ids: false,
        background: None,
        materials: None,
        oversize: 4.0,
        orthographic_distance: 1e8,
        start: Vec::new(),
    };

    /// The view shown until the pointer moves, yaw and pitch in degrees.
    #[must_use]
    pub fn with_start(mut self, yaw: f64, pitch: f64) -> Self {
        self.start = vec![(yaw, pitch)];
        self
    }

    /// Views the page turns through as it loads, the last shown until the pointer moves
    /// (for checking that switching orders leaves nothing of the previous ones).
    #[must_use]
    pub fn with_start_path(mut self, views: &[(f64, f64)]) -> Self {
        self.start = views.to_vec();
        self
    }
}

crate::page::page_setters!(TurnPageOptions: ids, background, materials);

impl Default for TurnPageOptions {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// What a turning page holds (from [`write_turn_html`]).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct TurnPage {
    /// The page.
    pub html: String,
    /// Regions of directions the script looks up.
    pub regions: usize,
    /// Distinct orders.
    pub orders: usize,
    /// Cycles whose order the script picks by the viewer's side of their planes.
    pub cycles: usize,
    /// Elements on the page.
    pub elements: usize,
}

/// A [`Presorted`] built from `geometry` as a self-contained page that turns the model with
/// the pointer: the pointer's position across the page maps to yaw (−180° to 180°) and pitch
/// (−90° to 90°), the rotation `Ry(yaw)·Rx(pitch)` of [`View::with_yaw_pitch_roll`].
///
/// - Every piece of the certified orders is an element under a fixed `matrix3d` (the model
///   at rest in `view`'s size, scale and projection; `view`'s rotation is ignored). One
///   custom property on the container carries the rotation to every element's individual
///   `rotate`, which composes after its `transform`; the container's `perspective`
///   projects (a huge one for orthographic views).
/// - `backface-visibility: hidden` culls, as the certificate assumes.
/// - The script finds the region whose spherical triangle holds the direction toward the
///   viewer (three dot products a region) and writes that order's precomputed `z-index` to
///   every element, hiding those the order does not use. A cycle left to a BSP tree in the
///   sorter is a table of orders here, one per side of its few planes, looked up by the
///   viewer's side of each.
///
/// `colour(face)` fills a face (ignored in ID mode).
///
/// # Errors
/// [`CertifiedOrdersError`]: the view's eye nearer than the certificate reaches, regions
/// without a certified order, or a cycle with too many planes.
pub fn write_turn_html(
    sorter: &Presorted,
    geometry: &Geometry,
    view: &View,
    options: &TurnPageOptions,
) -> Result<TurnPage, CertifiedOrdersError> {
    let colour = |face| crate::page::face_colour(options.materials.as_deref(), face);
    let (rest, eye, certified) = certified_at_rest(sorter, view)?;
    let distance = match rest.projection() {
        Projection::Orthographic => options.orthographic_distance,
        Projection::Perspective { distance } => distance,
    };
    let set = &*certified.pieces;
    let (w, h) = (rest.width(), rest.height());
    let origin = DVec3::new(f64::from(w) * 0.5, f64::from(h) * 0.5, 0.0);
    let flip = DMat3::from_diagonal(DVec3::new(1.0, -1.0, 1.0));
    let background = crate::page::background(options.background, options.ids);
    let mut page = crate::page::head("face-sort presorted", w, h, background);
    let _ = write!(
        page,
        "#s{{position:absolute;left:{cx}px;top:{cy}px;width:0;height:0;perspective:{d}px;perspective-origin:0 0;--r:0 0 1 0deg}}\n\
         #s>i,#s>b{{position:absolute;left:0;top:0;transform-origin:0 0;backface-visibility:hidden;rotate:var(--r);visibility:hidden}}\n\
         b{{width:0;height:0;border-style:solid;border-color:transparent}}\n",
        cx = num(origin.x),
        cy = num(origin.y),
        d = num(distance),
    );
    let maps = sprite_compose::polygon_maps(set, geometry, &rest);
    let elements_of = piece_classes(
        &mut page,
        set,
        &maps,
        geometry,
        &Placement {
            place: DMat4::from_translation(-origin),
            place_point: flip,
            scale: rest.scale(),
            turning: crate::page_pieces::Turning::Free,
        },
        &crate::page_pieces::face_fill(options.ids, &colour),
        options.oversize,
    );
    page.push_str("</style></head><body><div id=\"s\">\n");
    let mut elements = 0;
    for (p, of) in elements_of.iter().enumerate() {
        for (name, tag) in of {
            let _ = write!(page, "<{tag} class=\"{name}\"></{tag}>");
            elements += 1;
        }
        if p % 16 == 15 {
            page.push('\n');
        }
    }
    page.push_str("\n</div><script>\n");
    write_data(&mut page, &certified, &elements_of, eye, &options.start);
    page.push_str(LOOKUP);
    page.push_str(SCRIPT);
    page.push_str("</script></body></html>\n");
    Ok(TurnPage {
        html: page,
        regions: certified.regions.len(),
        orders: certified.orders.len(),
        cycles: certified.cores.len(),
        elements,
    })
}

/// `view` at rest (its rotation ignored: the page turns it), the eye's distance from the
/// centre in model units (`None`: orthographic), and the orders certified for that viewer.
pub(crate) fn certified_at_rest(
    sorter: &Presorted,
    view: &View,
) -> Result<(View, Option<f64>, CertifiedOrders), CertifiedOrdersError> {
    let rest = view.with_rotation(DMat3::IDENTITY);
    let eye = match rest.projection() {
        Projection::Orthographic => None,
        Projection::Perspective { distance } => Some(distance / rest.scale()),
    };
    let certified = sorter.certified_orders(eye)?;
    Ok((rest, eye, certified))
}

/// Polygon indices in base64, little-endian, two bytes each when every index fits (`wide`:
/// four); the script reads them as typed arrays.
fn base64_ids(values: impl IntoIterator<Item = u32>, wide: bool) -> String {
    let bytes: Vec<u8> = values
        .into_iter()
        .flat_map(|v| {
            let b = v.to_le_bytes();
            if wide { b.to_vec() } else { b[..2].to_vec() }
        })
        .collect();
    base64::engine::general_purpose::STANDARD.encode(bytes)
}

/// Little-endian f64 bytes in base64.
fn base64_f64(values: impl IntoIterator<Item = f64>) -> String {
    let bytes: Vec<u8> = values.into_iter().flat_map(f64::to_le_bytes).collect();
    base64::engine::general_purpose::STANDARD.encode(bytes)
}

/// The tables the script reads:
/// - `N`: elements per polygon; `W`: whether polygon indices take four bytes (else two);
/// - `E`: the eye's distance from the centre in model units (0: orthographic); `S`: the
///   views to turn through as it loads;
/// - `R`: per region, its three inward edge normals, and `RO` its order;
/// - `O[o]`: order `o`'s polygons in paint order, the `i`-th at `z-index` `(i + 1)·K`;
///   `OC[o]`: `[cycle, z]` pairs, the cycle's polygons taking `z-index` `z, z + 1, …`
///   between the polygons its step sits between;
/// - `C[c]`: a cycle's planes (`[nx, ny, nz, offset]` each) and, per key, its polygons.
pub(crate) fn write_data(
    page: &mut String,
    certified: &CertifiedOrders,
    elements_of: &[Vec<(String, char)>],
    eye: Option<f64>,
    start: &[(f64, f64)],
) {
    let wide = elements_of.len() > usize::from(u16::MAX);
    let core_size = |c: u32| {
        certified.cores[c as usize]
            .orders
            .first()
            .map_or(0, |o| o.len() as u32)
    };
    // K: more than the cycles' polygons between two consecutive pieces of any order.
    let mut k = 1u32;
    for steps in &certified.orders {
        let mut run = 0;
        for step in steps {
            match *step {
                OrderStep::Piece(_) => run = 0,
                OrderStep::Core(c) => {
                    run += core_size(c);
                    k = k.max(run + 1);
                }
            }
        }
    }
    let _ = writeln!(
        page,
        "const N={:?};\nconst W={};\nconst K={k};\nconst E={};\nconst S=[{}];",
        elements_of.iter().map(Vec::len).collect::<Vec<_>>(),
        u8::from(wide),
        eye.map_or("0".to_owned(), |e| format!("{e:e}")),
        start
            .iter()
            .map(|(yaw, pitch)| format!("[{},{}]", num(*yaw), num(*pitch)))
            .collect::<Vec<_>>()
            .join(","),
    );
    let _ = writeln!(
        page,
        "const R=\"{}\";\nconst RO={:?};",
        base64_f64(
            certified
                .regions
                .iter()
                .flat_map(|r| r.edge_normals.iter().flat_map(|e| e.to_array()))
        ),
        certified
            .regions
            .iter()
            .map(|r| r.order)
            .collect::<Vec<_>>(),
    );
    page.push_str("const O=[");
    let mut slots = Vec::new();
    for steps in &certified.orders {
        let (mut pieces, mut cores) = (Vec::new(), Vec::new());
        let mut z = 0;
        for step in steps {
            match *step {
                OrderStep::Piece(p) => {
                    pieces.push(p);
                    z = pieces.len() as u32 * k;
                }
                OrderStep::Core(c) => {
                    cores.push([c, z + 1]);
                    z += core_size(c);
                }
            }
        }
        let _ = write!(page, "\"{}\",", base64_ids(pieces, wide));
        slots.push(cores);
    }
    let _ = writeln!(page, "];\nconst OC={slots:?};");
    page.push_str("const C=[");
    for core in &certified.cores {
        let _ = write!(
            page,
            "[\"{}\",\"{}\"],",
            base64_f64(core.planes.iter().flat_map(|p| {
                let n = p.normal();
                [n.x, n.y, n.z, p.offset()]
            })),
            base64_ids(core.orders.iter().flatten().copied(), wide)
        );
    }
    page.push_str("];\n");
}

/// The lookup both turning pages share (this one and the canvas player): the tables
/// decoded; `viewer(yaw, pitch)`, the quaternion of `Ry(yaw)·Rx(pitch)`; `regionOf(u)`, the
/// order of the region the direction toward the viewer `u` is deepest inside (on a shared
/// edge either is exact); `keyOf(c, u)`, a cycle's key by the viewer's side of its planes.
pub(crate) const LOOKUP: &str = r#"const bytes=s=>Uint8Array.from(atob(s),c=>c.charCodeAt(0)).buffer;
const ids=s=>W?new Uint32Array(bytes(s)):new Uint16Array(bytes(s));
const regions=new Float64Array(bytes(R)),orders=O.map(ids);
const cycles=C.map(([p,t])=>{const planes=new Float64Array(bytes(p)),all=ids(t),n=all.length>>(planes.length/4);
 return [planes,n,all];});
function viewer(yaw,pitch){
 const a=yaw*Math.PI/360,b=pitch*Math.PI/360,cy=Math.cos(a),sy=Math.sin(a),cp=Math.cos(b),sp=Math.sin(b);
 return [cy*sp,sy*cp,-sy*sp,cy*cp];}
function regionOf(u){let o=0,best=-Infinity;
 for(let r=0;r<RO.length;r++){const k=9*r;let d=Infinity;
  for(let j=0;j<9;j+=3)d=Math.min(d,regions[k+j]*u[0]+regions[k+j+1]*u[1]+regions[k+j+2]*u[2]);
  if(d>best){best=d;o=RO[r];}}
 return o;}
function keyOf(c,u){const planes=cycles[c][0],t=E>0?E:1,m=E>0?1:0;let key=0;
 for(let i=0;4*i<planes.length;i++)if(t*(planes[4*i]*u[0]+planes[4*i+1]*u[1]+planes[4*i+2]*u[2])-m*planes[4*i+3]>=0)key|=1<<i;
 return key;}
"#;

/// The page's script after [`LOOKUP`]: `z-index` and visibility out.
const SCRIPT: &str = r#"const s=document.getElementById('s'),el=s.children,first=[0];
for(const k of N)first.push(first[first.length-1]+k);
let shown=-1,keys=[];
function put(p,z){for(let e=first[p];e<first[p+1];e++){el[e].style.zIndex=z;el[e].style.visibility=z?'visible':'hidden';}}
function cycle(c,key,z){const [,n,all]=cycles[c];for(let i=0;i<n;i++)put(all[key*n+i],z&&z+i);}
function turn(yaw,pitch){
 const [x,y,z,w]=viewer(yaw,pitch),l=Math.hypot(x,y,z);
 s.style.setProperty('--r',l>1e-12?`${-x/l} ${y/l} ${-z/l} ${2*Math.atan2(l,w)}rad`:'0 0 1 0deg');
 // Toward the viewer in the model: the third row of the rotation.
 const u=[2*(x*z-w*y),2*(y*z+w*x),1-2*(x*x+y*y)];
 const o=regionOf(u);
 if(o!==shown){
  if(shown>=0){for(const p of orders[shown])put(p,0);OC[shown].forEach(([c],j)=>cycle(c,keys[j],0));}
  orders[o].forEach((p,i)=>put(p,(i+1)*K));shown=o;keys=OC[o].map(()=>-1);}
 OC[o].forEach(([c,z],j)=>{const key=keyOf(c,u);
  if(key!==keys[j]){cycle(c,key,z);keys[j]=key;}});
}
const h=location.hash.slice(1).split(',').map(Number);
for(const v of h.length===2&&h.every(Number.isFinite)?[h]:S.length?S:[[0,0]])turn(...v);
addEventListener('pointermove',e=>turn(360*e.clientX/innerWidth-180,180*e.clientY/innerHeight-90));
"#;
