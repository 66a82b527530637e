//! The canvas players: one `<canvas>` and a small script that, per frame, projects the
//! vertices with one rotation, looks up the order (a bake's cell, or a certified region),
//! culls and fills the pieces in that order. They order nothing.
//!
//! Both players share the pieces' tables and the painter ([`pieces_js`], [`PAINTER`]):
//! vertices once (32-bit floats, centred model space), each piece's corner indices (16-bit
//! where every index fits), its plane's normal (64-bit: the cull test decides by its sign),
//! face and colour. A frame is `project(R)` then `paint(list)`: the view's projection of
//! CONVENTIONS.md and its cull test, in f64. In ID mode there is no anti-aliasing: every
//! piece fills the pixels whose centres it holds with its face's ID colour (a span per row,
//! written into the image), as CONVENTIONS.md's ID images are sampled. Otherwise the canvas
//! fills paths, consecutive drawn pieces of one face as one path (no anti-aliased seam
//! where a face was cut), each stroked half a pixel wide in its own colour under the pieces
//! painted after it, so that anti-aliased edges between neighbours do not let the
//! background through.

use std::collections::HashMap;
use std::fmt::Write as _;

use aspect_bake::{Bake, Spin};
use face_sort::{
    CertifiedOrdersError, CullMode, FrontFace, Geometry, PolygonSet, Presorted, Projection, View,
};
use glam::{DMat3, DVec3};

use crate::spin::SpinOptions;
use crate::turn_page::{TurnPage, TurnPageOptions};

/// Little-endian bytes of `values`, base64 (for the page's typed arrays).
fn base64_of<T: Copy>(values: &[T], bytes: impl Fn(T) -> Vec<u8>) -> String {
    use base64::Engine as _;
    let raw: Vec<u8> = values.iter().flat_map(|&v| bytes(v)).collect();
    base64::engine::general_purpose::STANDARD.encode(raw)
}

/// A number as JavaScript reads it back bit for bit (Rust's shortest round-trip form).
fn num(v: f64) -> String {
    format!("{v}")
}

/// The 9 entries of `m`, row by row, as a JavaScript array.
fn rows(m: DMat3) -> String {
    let r = m.transpose().to_cols_array();
    format!("[{}]", r.map(num).join(","))
}

/// The page up to its script: a `<canvas>` of the view's size on the background.
fn page_head(title: &str, view: &View, background: [u8; 4]) -> String {
    let (w, h) = (view.width(), view.height());
    let mut page = crate::page::head(title, w, h, background);
    page.push_str(&format!(
        "canvas{{display:block}}</style></head>\n\
         <body><canvas id=\"c\" width=\"{w}\" height=\"{h}\" style=\"width:{w}px;height:{h}px\"></canvas>\n<script>\n"
    ));
    page
}

/// `const P={…};`: the pieces of `set` (centred on `view`'s centre after `shift`) and the
/// camera of `view` (its rotation aside), read by [`PAINTER`]. Also whether indices are
/// 32-bit (`wide`), for the page's other index tables.
fn pieces_js(
    set: &PolygonSet,
    shift: DVec3,
    view: &View,
    colour: &dyn Fn(u32) -> [u8; 4],
    ids: bool,
    background: [u8; 4],
) -> (String, bool) {
    // Unique vertices, bit for bit.
    let mut index: HashMap<[u64; 3], u32> = HashMap::new();
    let mut vertices: Vec<f32> = Vec::new();
    let (mut corners, mut offsets) = (Vec::new(), vec![0u32]);
    let (mut normals, mut colours, mut faces) = (Vec::new(), Vec::new(), Vec::new());
    for i in 0..set.len() {
        for c in set.corners(i) {
            let c = *c + shift;
            let key = c.to_array().map(f64::to_bits);
            let k = *index.entry(key).or_insert_with(|| {
                vertices.extend(c.to_array().map(|v| v as f32));
                (vertices.len() / 3 - 1) as u32
            });
            corners.push(k);
        }
        offsets.push(corners.len() as u32);
        normals.extend(set.plane(i).normal().to_array());
        let face = set.face(i);
        faces.push(face);
        colours.extend(if ids {
            crate::id_colour(face)
        } else {
            colour(face)
        });
    }
    let distance = match view.projection() {
        Projection::Orthographic => 0.0,
        Projection::Perspective { distance } => distance,
    };
    // +1: faces whose test value is positive are drawn; −1: negative; 0: every face.
    let sign = match (view.cull(), view.front_face()) {
        (CullMode::None, _) => 0,
        (CullMode::Back, FrontFace::CounterClockwise) | (CullMode::Front, FrontFace::Clockwise) => {
            1
        }
        _ => -1,
    };
    let wide = vertices.len() / 3 > usize::from(u16::MAX) || set.len() > usize::from(u16::MAX);
    let u32s = |v: &[u32]| base64_of(v, |x| x.to_le_bytes().to_vec());
    let (principal, offset) = (view.principal_point(), view.view_offset());
    let js = format!(
        "const P={{f:\"{}\",v:\"{}\",n:\"{}\",ix:\"{}\",off:\"{}\",col:\"{}\",s:{},d:{},px:{},py:{},\
         t:[{},{},{}],sign:{sign},w:{},h:{},ids:{ids},wide:{wide},bg:\"{}\",bgrgb:[{},{},{}]}};\n",
        u32s(&faces),
        base64_of(&vertices, |x: f32| x.to_le_bytes().to_vec()),
        base64_of(&normals, |x: f64| x.to_le_bytes().to_vec()),
        index_base64(&corners, wide),
        u32s(&offsets),
        base64_of(&colours, |x: u8| vec![x]),
        num(view.scale()),
        num(distance),
        num(principal.x),
        num(principal.y),
        num(offset.x),
        num(offset.y),
        num(offset.z),
        view.width(),
        view.height(),
        crate::numbers::hex(background),
        background[0],
        background[1],
        background[2],
    );
    (js, wide)
}

/// Indices as 16-bit integers, or 32-bit when `wide`, base64.
fn index_base64(values: &[u32], wide: bool) -> String {
    if wide {
        base64_of(values, |x| x.to_le_bytes().to_vec())
    } else {
        base64_of(values, |x| (x as u16).to_le_bytes().to_vec())
    }
}

/// A picture bake ([`aspect_bake::bake_picture`]) as a self-contained page with one
/// `<canvas>` that turns the model once per `period_s` (module docs).
///
/// Besides the pieces, the page holds each cell's drawn list as piece indices (`lists`,
/// [`aspect_bake::drawn_lists`]: full lists, not deltas). A frame applies the spin's
/// rotation `R(θ) = C₀ + C₁·cos θ + C₂·sin θ`, finds the cell holding `θ` by binary search
/// as [`Bake::cell_at`] does, and paints the cell's list. `paused_at_s` draws one frame at
/// that time; a page address `#S` (seconds) does too.
#[must_use]
pub fn write_canvas_spin_html(
    bake: &Bake,
    lists: &[Vec<u32>],
    spin: &Spin,
    geometry: &Geometry,
    options: &SpinOptions,
) -> String {
    let colour = |face| crate::page::face_colour(options.materials.as_deref(), face);
    let background = crate::page::background(options.background, options.ids);
    let view = spin.view_at(0.0);
    let shift = geometry.bounds().centre() - view.centre();
    let (pieces, wide) = pieces_js(
        bake.polygons(),
        shift,
        &view,
        &colour,
        options.ids,
        background,
    );
    let mut order = Vec::new();
    let mut cell_offsets = vec![0u32];
    for list in lists {
        order.extend_from_slice(list);
        cell_offsets.push(order.len() as u32);
    }
    let lows: Vec<String> = bake.cells().iter().map(|c| num(c.range.lo)).collect();
    let [c0, c1, c2] = spin.rodrigues();
    let mut page = page_head("spin", &view, background);
    page.push_str(&pieces);
    let _ = writeln!(
        page,
        "const D={{ord:\"{}\",co:\"{}\",lo:[{}],c0:{},c1:{},c2:{},period:{},start:{},paused:{}}};",
        index_base64(&order, wide),
        base64_of(&cell_offsets, |x: u32| x.to_le_bytes().to_vec()),
        lows.join(","),
        rows(c0),
        rows(c1),
        rows(c2),
        num(options.period_s),
        num(bake.domain().lo),
        options.paused_at_s.map_or("null".to_owned(), num),
    );
    page.push_str(PAINTER);
    page.push_str(SPIN);
    page.push_str("</script></body></html>\n");
    page
}

/// A [`Presorted`] built from `geometry` as a self-contained page with one `<canvas>` that
/// turns the model with the pointer (module docs), as [`write_turn_html`](crate::write_turn_html)
/// does with CSS: the pointer maps to yaw (−180° to 180°) and pitch (−90° to 90°) of
/// `Ry(yaw)·Rx(pitch)`, the script finds the region of directions holding the viewer and
/// each cycle's order by the viewer's side of its planes (the same lookup as the CSS page's),
/// and paints that order. A page address `#yaw,pitch` shows that view.
///
/// # Errors
/// As [`write_turn_html`](crate::write_turn_html).
pub fn write_canvas_turn_html(
    sorter: &Presorted,
    geometry: &Geometry,
    view: &View,
    options: &TurnPageOptions,
) -> Result<TurnPage, CertifiedOrdersError> {
    let colour = |face| crate::page::face_colour(options.materials.as_deref(), face);
    let background = crate::page::background(options.background, options.ids);
    let (rest, eye, certified) = crate::turn_page::certified_at_rest(sorter, view)?;
    let shift = geometry.bounds().centre() - rest.centre();
    let (pieces, _) = pieces_js(
        &certified.pieces,
        shift,
        &rest,
        &colour,
        options.ids,
        background,
    );
    let mut page = page_head("face-sort presorted", &rest, background);
    page.push_str(&pieces);
    // The lookup's tables index pieces (one "element" each).
    let one_each: Vec<Vec<(String, char)>> =
        vec![vec![(String::new(), 'i')]; certified.pieces.len()];
    crate::turn_page::write_data(&mut page, &certified, &one_each, eye, &options.start);
    page.push_str(crate::turn_page::LOOKUP);
    page.push_str(PAINTER);
    page.push_str(TURN);
    page.push_str("</script></body></html>\n");
    Ok(TurnPage {
        html: page,
        regions: certified.regions.len(),
        orders: certified.orders.len(),
        cycles: certified.cores.len(),
        elements: certified.pieces.len(),
    })
}

/// The painter both players share: decode the pieces, `project(R)`, `paint(each)`.
const PAINTER: &str = r#"function arr(s,T){const b=atob(s),u=new Uint8Array(b.length);for(let i=0;i<b.length;i++)u[i]=b.charCodeAt(i);return new T(u.buffer);}
const V=arr(P.v,Float32Array),NM=arr(P.n,Float64Array),IX=arr(P.ix,P.wide?Uint32Array:Uint16Array),OFF=arr(P.off,Uint32Array),
COL=arr(P.col,Uint8Array),FACE=arr(P.f,Uint32Array);
const nv=V.length/3,X=new Float64Array(nv),Y=new Float64Array(nv),VX=new Float64Array(nv),VY=new Float64Array(nv),VZ=new Float64Array(nv);
const FILL=[];for(let p=0;p<OFF.length-1;p++)FILL.push("rgba("+COL[4*p]+","+COL[4*p+1]+","+COL[4*p+2]+","+(COL[4*p+3]/255)+")");
const cv=document.getElementById("c"),dpr=window.devicePixelRatio||1;cv.width=P.w*dpr;cv.height=P.h*dpr;
const ctx=cv.getContext("2d",{alpha:false});ctx.scale(dpr,dpr);ctx.imageSmoothingEnabled=false;ctx.lineJoin="round";ctx.lineWidth=1;
const ROT=new Float64Array(9);
// ID mode: no anti-aliasing (module docs).
const IMG=P.ids?ctx.createImageData(P.w,P.h):null,PIX=P.ids?new Uint32Array(IMG.data.buffer):null;
function span(a,b,p){const m=b-a;let y0=Infinity,y1=-Infinity;
for(let j=a;j<b;j++){const y=Y[IX[j]];if(y<y0)y0=y;if(y>y1)y1=y;}
const c=(255<<24)|(COL[4*p+2]<<16)|(COL[4*p+1]<<8)|COL[4*p];
for(let r=Math.max(0,Math.ceil(y0-0.5));r<=Math.min(P.h-1,Math.floor(y1-0.5));r++){const yc=r+0.5;let xl=Infinity,xr=-Infinity;
for(let j=0;j<m;j++){const i0=IX[a+j],i1=IX[a+(j+1)%m],ya=Y[i0],yb=Y[i1];
if((ya<=yc&&yb>yc)||(yb<=yc&&ya>yc)){const x=X[i0]+(yc-ya)*(X[i1]-X[i0])/(yb-ya);if(x<xl)xl=x;if(x>xr)xr=x;}}
for(let col=Math.max(0,Math.ceil(xl-0.5));col<=Math.min(P.w-1,Math.ceil(xr-0.5)-1);col++)PIX[r*P.w+col]=c;}}
// Every vertex through R and the view's projection.
function project(){const R=ROT;const sc=P.s,d=P.d;
for(let i=0;i<nv;i++){const x=V[3*i],y=V[3*i+1],z=V[3*i+2];
const vx=ROT[0]*x+ROT[1]*y+ROT[2]*z+P.t[0],vy=ROT[3]*x+ROT[4]*y+ROT[5]*z+P.t[1],vz=ROT[6]*x+ROT[7]*y+ROT[8]*z+P.t[2];
VX[i]=vx;VY[i]=vy;VZ[i]=vz;const w=d>0?1-sc*vz/d:1;X[i]=P.px+sc*vx/w;Y[i]=P.py-sc*vy/w;}}
// Clears, then `each(draw)` calls draw(p) for the pieces in paint order; draw culls and fills.
function paint(each){const sc=P.s,d=P.d,ez=d>0?d/sc:0;let open=-1;
if(P.ids)PIX.fill((255<<24)|(P.bgrgb[2]<<16)|(P.bgrgb[1]<<8)|P.bgrgb[0]);else{ctx.fillStyle=P.bg;ctx.fillRect(0,0,P.w,P.h);}
const flush=()=>{if(open<0)return;ctx.fillStyle=FILL[open];ctx.fill();ctx.strokeStyle=FILL[open];ctx.stroke();open=-1;};
each(p=>{const a=OFF[p],b=OFF[p+1],R=ROT;
if(P.sign!==0){const nx=NM[3*p],ny=NM[3*p+1],nz=NM[3*p+2];
const rx=ROT[0]*nx+ROT[1]*ny+ROT[2]*nz,ry=ROT[3]*nx+ROT[4]*ny+ROT[5]*nz,rz=ROT[6]*nx+ROT[7]*ny+ROT[8]*nz;
const v0=IX[a],f=d>0?(rx*(-VX[v0])+ry*(-VY[v0])+rz*(ez-VZ[v0])):rz;
if(!(P.sign*f>0))return;}
if(P.ids){span(a,b,p);return;}
if(open<0||FACE[p]!==FACE[open]||FILL[p]!==FILL[open]){flush();ctx.beginPath();open=p;}
ctx.moveTo(X[IX[a]],Y[IX[a]]);for(let j=a+1;j<b;j++)ctx.lineTo(X[IX[j]],Y[IX[j]]);ctx.closePath();});
flush();
if(P.ids)ctx.putImageData(IMG,0,0);}
"#;

/// The spin player: the cell of the time's angle, its list.
const SPIN: &str = r#"const ORD=arr(D.ord,P.wide?Uint32Array:Uint16Array),CO=arr(D.co,Uint32Array);
function cellAt(deg){const lo=D.lo[0],a=(deg>=lo&&deg<lo+360)?deg:lo+(((deg-lo)%360)+360)%360;let a0=0,a1=D.lo.length;while(a0<a1){const m=(a0+a1)>>1;if(D.lo[m]<=a)a0=m+1;else a1=m;}return Math.max(a0-1,0);}
function frame(deg){const th=deg*Math.PI/180,c=Math.cos(th),s=Math.sin(th);
for(let i=0;i<9;i++)ROT[i]=D.c0[i]+D.c1[i]*c+D.c2[i]*s;
project();const cell=cellAt(deg);paint(draw=>{for(let k=CO[cell];k<CO[cell+1];k++)draw(ORD[k]);});}
function degreesAt(t){return D.start+360*(((t%D.period)+D.period)%D.period)/D.period;}
const hash=parseFloat(location.hash.slice(1));
if(D.paused!==null||!isNaN(hash)){frame(degreesAt(isNaN(hash)?D.paused:hash));}
else{const t0=performance.now();const tick=now=>{frame(degreesAt((now-t0)/1000));requestAnimationFrame(tick);};requestAnimationFrame(tick);}
"#;

/// The turn player: the pointer's view, its region's order with each cycle's by key.
const TURN: &str = r#"let pending=null;
function show(yaw,pitch){const q=viewer(yaw,pitch),x=q[0],y=q[1],z=q[2],w=q[3];
ROT[0]=1-2*(y*y+z*z);ROT[1]=2*(x*y-z*w);ROT[2]=2*(x*z+y*w);ROT[3]=2*(x*y+z*w);ROT[4]=1-2*(x*x+z*z);ROT[5]=2*(y*z-x*w);
ROT[6]=2*(x*z-y*w);ROT[7]=2*(y*z+x*w);ROT[8]=1-2*(x*x+y*y);
const u=[ROT[6],ROT[7],ROT[8]],o=regionOf(u),steps=orders[o],slots=OC[o];
project();
paint(draw=>{let j=0;const cores=c=>{const [,n,all]=cycles[c[0]],key=keyOf(c[0],u);for(let i=0;i<n;i++)draw(all[key*n+i]);};
for(let i=0;i<steps.length;i++){while(j<slots.length&&Math.floor((slots[j][1]-1)/K)<=i)cores(slots[j++]);draw(steps[i]);}
while(j<slots.length)cores(slots[j++]);});}
const h=location.hash.slice(1).split(',').map(Number);
for(const v of h.length===2&&h.every(Number.isFinite)?[h]:S.length?S:[[0,0]])show(...v);
addEventListener('pointermove',e=>{const v=[360*e.clientX/innerWidth-180,180*e.clientY/innerHeight-90];
if(pending===null)requestAnimationFrame(()=>{show(...pending);pending=null;});pending=v;});
"#;
