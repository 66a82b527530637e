//! The canvas player of a picture bake: one `<canvas>` and a small script that, per frame,
//! projects the vertices with one rotation, looks up the cell, culls and fills the pieces in
//! the cell's order. It orders nothing.

use std::collections::HashMap;
use std::fmt::Write as _;

use aspect_bake::{Bake, Spin};
use face_sort::{CullMode, FrontFace, Geometry, Projection};
use glam::DMat3;

use crate::spin::SpinOptions;

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

/// A picture bake ([`aspect_bake::bake_picture`]) as a self-contained page with one
/// `<canvas>` that turns the model once per `period_s`.
///
/// The page holds the bake's pieces once (their corners as unique vertices, 32-bit floats
/// in centred model space; each piece's corner indices, its plane's normal as 64-bit
/// floats, since the cull test decides by its sign, and its colour) and each
/// cell's drawn list as piece indices (`lists`, [`aspect_bake::drawn_lists`]): full lists,
/// not deltas; indices are 16-bit integers where they all fit, else 32-bit. A frame is the spin's rotation
/// `R(θ) = C₀ + C₁·cos θ + C₂·sin θ` applied to every vertex, the projection of
/// CONVENTIONS.md (the spin's view: scale, principal point, perspective distance), the cell
/// holding `θ` found by binary search as [`Bake::cell_at`] does, and the cell's pieces
/// filled in order where they face the viewer (the view's cull test, in f64).
///
/// In ID mode there is no anti-aliasing: every piece fills the pixels whose centres it
/// holds with its face's ID colour (a span per row, written into the image), as
/// CONVENTIONS.md's ID images are sampled. Otherwise the canvas fills paths, consecutive
/// drawn pieces of one face as one path (no anti-aliased seam where the bake cut a face),
/// and each path is also stroked
/// half a pixel wide in its own colour, under the pieces painted after it, so that
/// anti-aliased edges between neighbours do not let the background through. `paused_at_s` draws one frame at that time; a page address `#S`
/// (seconds) does too.
#[must_use]
pub fn write_canvas_spin_html(
    bake: &Bake,
    lists: &[Vec<u32>],
    spin: &Spin,
    geometry: &Geometry,
    colour: &dyn Fn(u32) -> [u8; 4],
    options: &SpinOptions,
) -> String {
    let view = spin.view_at(0.0);
    let pieces = bake.polygons();
    let centre_shift = geometry.bounds().centre() - view.centre();
    // Unique vertices, bit for bit.
    let mut index: HashMap<[u64; 3], u32> = HashMap::new();
    let mut vertices: Vec<f32> = Vec::new();
    let (mut corners, mut offsets) = (Vec::new(), vec![0u32]);
    let (mut normals, mut colours, mut faces) = (Vec::new(), Vec::new(), Vec::new());
    for i in 0..pieces.len() {
        for c in pieces.corners(i) {
            let c = *c + centre_shift;
            let key = c.to_array().map(f64::to_bits);
            let k = *index.entry(key).or_insert_with(|| {
                vertices.extend(c.to_array().map(|v| v as f32));
                (vertices.len() / 3 - 1) as u32
            });
            corners.push(k);
        }
        offsets.push(corners.len() as u32);
        normals.extend(pieces.plane(i).normal().to_array());
        let face = pieces.face(i);
        faces.push(face);
        colours.extend(if options.ids {
            crate::id_colour(face)
        } else {
            colour(face)
        });
    }
    let mut order = Vec::new();
    let mut cell_offsets = vec![0u32];
    for list in lists {
        order.extend_from_slice(list);
        cell_offsets.push(order.len() as u32);
    }
    let lows: Vec<String> = bake.cells().iter().map(|c| num(c.range.lo)).collect();
    // R(θ) = C0 + C1·cos θ + C2·sin θ, from three rotations of the spin.
    let (r0, r90, r180) = (
        spin.rotation_rad(0.0),
        spin.rotation_rad(std::f64::consts::FRAC_PI_2),
        spin.rotation_rad(std::f64::consts::PI),
    );
    let c0 = (r0 + r180) * 0.5;
    let (c1, c2) = ((r0 - r180) * 0.5, r90 - c0);
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
    let (w, h) = (view.width(), view.height());
    let principal = view.principal_point();
    let offset = view.view_offset();
    let background = crate::svg::hex(options.background);
    // Index arrays as 16-bit integers where every index fits (the page says which).
    let wide = vertices.len() / 3 > usize::from(u16::MAX) || pieces.len() > usize::from(u16::MAX);
    let u32s = |v: &[u32]| base64_of(v, |x| x.to_le_bytes().to_vec());
    let indices = |v: &[u32]| {
        if wide {
            u32s(v)
        } else {
            base64_of(v, |x| (x as u16).to_le_bytes().to_vec())
        }
    };
    let mut page = String::new();
    let _ = write!(
        page,
        "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>spin</title>\n\
         <style>html,body{{margin:0;background:{background}}}canvas{{display:block}}</style></head>\n\
         <body><canvas id=\"c\" width=\"{w}\" height=\"{h}\" style=\"width:{w}px;height:{h}px\"></canvas>\n<script>\n"
    );
    let _ = writeln!(
        page,
        "const D={{f:\"{}\",v:\"{}\",n:\"{}\",ix:\"{}\",off:\"{}\",col:\"{}\",ord:\"{}\",co:\"{}\",lo:[{}],\
         c0:{},c1:{},c2:{},s:{},d:{},px:{},py:{},t:[{},{},{}],sign:{sign},w:{w},h:{h},\
         period:{},start:{},ids:{},wide:{wide},bg:\"{background}\",bgrgb:[{},{},{}],paused:{}}};",
        u32s(&faces),
        base64_of(&vertices, |x: f32| x.to_le_bytes().to_vec()),
        base64_of(&normals, |x: f64| x.to_le_bytes().to_vec()),
        indices(&corners),
        u32s(&offsets),
        base64_of(&colours, |x: u8| vec![x]),
        indices(&order),
        u32s(&cell_offsets),
        lows.join(","),
        rows(c0),
        rows(c1),
        rows(c2),
        num(view.scale()),
        num(distance),
        num(principal.x),
        num(principal.y),
        num(offset.x),
        num(offset.y),
        num(offset.z),
        num(options.period_s),
        num(bake.domain().lo),
        options.ids,
        options.background[0],
        options.background[1],
        options.background[2],
        options.paused_at_s.map_or("null".to_owned(), num),
    );
    page.push_str(PLAYER);
    page.push_str("</script></body></html>\n");
    page
}

/// The player: decode, then per frame project, look up, cull and fill.
const PLAYER: &str = r#"function arr(s,T){const b=atob(s),u=new Uint8Array(b.length);for(let i=0;i<b.length;i++)u[i]=b.charCodeAt(i);return new T(u.buffer);}
const V=arr(D.v,Float32Array),N=arr(D.n,Float64Array),IX=arr(D.ix,D.wide?Uint32Array:Uint16Array),OFF=arr(D.off,Uint32Array),
COL=arr(D.col,Uint8Array),ORD=arr(D.ord,D.wide?Uint32Array:Uint16Array),CO=arr(D.co,Uint32Array),FACE=arr(D.f,Uint32Array);
const n=V.length/3,X=new Float64Array(n),Y=new Float64Array(n),VX=new Float64Array(n),VY=new Float64Array(n),VZ=new Float64Array(n);
const FILL=[];for(let p=0;p<OFF.length-1;p++)FILL.push("rgba("+COL[4*p]+","+COL[4*p+1]+","+COL[4*p+2]+","+(COL[4*p+3]/255)+")");
const cv=document.getElementById("c"),dpr=window.devicePixelRatio||1;cv.width=D.w*dpr;cv.height=D.h*dpr;
const ctx=cv.getContext("2d",{alpha:false});ctx.scale(dpr,dpr);ctx.imageSmoothingEnabled=false;ctx.lineJoin="round";ctx.lineWidth=1;
const R=new Float64Array(9),COL_BG=D.bgrgb;
function cellAt(deg){const lo=D.lo[0],a=(deg>=lo&&deg<lo+360)?deg:lo+(((deg-lo)%360)+360)%360;let a0=0,a1=D.lo.length;while(a0<a1){const m=(a0+a1)>>1;if(D.lo[m]<=a)a0=m+1;else a1=m;}return Math.max(a0-1,0);}
function frame(deg){
const th=deg*Math.PI/180,c=Math.cos(th),s=Math.sin(th);
for(let i=0;i<9;i++)R[i]=D.c0[i]+D.c1[i]*c+D.c2[i]*s;
const sc=D.s,d=D.d;
for(let i=0;i<n;i++){const x=V[3*i],y=V[3*i+1],z=V[3*i+2];
const vx=R[0]*x+R[1]*y+R[2]*z+D.t[0],vy=R[3]*x+R[4]*y+R[5]*z+D.t[1],vz=R[6]*x+R[7]*y+R[8]*z+D.t[2];
VX[i]=vx;VY[i]=vy;VZ[i]=vz;const w=d>0?1-sc*vz/d:1;X[i]=D.px+sc*vx/w;Y[i]=D.py-sc*vy/w;}
if(D.ids)PIX.fill((255<<24)|(COL_BG[2]<<16)|(COL_BG[1]<<8)|COL_BG[0]);else{ctx.fillStyle=D.bg;ctx.fillRect(0,0,D.w,D.h);}
const cell=cellAt(deg),ez=d>0?d/sc:0;let open=-1;
const flush=()=>{if(open<0)return;ctx.fillStyle=FILL[open];ctx.fill();if(!D.ids){ctx.strokeStyle=FILL[open];ctx.stroke();}open=-1;};
for(let k=CO[cell];k<CO[cell+1];k++){const p=ORD[k],a=OFF[p],b=OFF[p+1];
if(D.sign!==0){const nx=N[3*p],ny=N[3*p+1],nz=N[3*p+2];
const rx=R[0]*nx+R[1]*ny+R[2]*nz,ry=R[3]*nx+R[4]*ny+R[5]*nz,rz=R[6]*nx+R[7]*ny+R[8]*nz;
const v0=IX[a],f=d>0?(rx*(-VX[v0])+ry*(-VY[v0])+rz*(ez-VZ[v0])):rz;
if(!(D.sign*f>0))continue;}
if(D.ids){span(a,b,p);continue;}
if(open<0||FACE[p]!==FACE[open]||FILL[p]!==FILL[open]){flush();ctx.beginPath();open=p;}
ctx.moveTo(X[IX[a]],Y[IX[a]]);for(let j=a+1;j<b;j++)ctx.lineTo(X[IX[j]],Y[IX[j]]);ctx.closePath();}
flush();
if(D.ids)ctx.putImageData(IMG,0,0);
}
// ID mode: no anti-aliasing. Each convex piece fills the pixels whose centres it holds, row
// by row (its span on the row through the centres), straight into the image.
const IMG=D.ids?ctx.createImageData(D.w,D.h):null,PIX=D.ids?new Uint32Array(IMG.data.buffer):null;
function span(a,b,p){const m=b-a;let y0=Infinity,y1=-Infinity;
for(let j=a;j<b;j++){const y=Y[IX[j]];if(y<y0)y0=y;if(y>y1)y1=y;}
const c=(255<<24)|(COL[4*p+2]<<16)|(COL[4*p+1]<<8)|COL[4*p];
for(let r=Math.max(0,Math.ceil(y0-0.5));r<=Math.min(D.h-1,Math.floor(y1-0.5));r++){const yc=r+0.5;let xl=Infinity,xr=-Infinity;
for(let j=0;j<m;j++){const i0=IX[a+j],i1=IX[a+(j+1)%m],ya=Y[i0],yb=Y[i1];
if((ya<=yc&&yb>yc)||(yb<=yc&&ya>yc)){const x=X[i0]+(yc-ya)*(X[i1]-X[i0])/(yb-ya);if(x<xl)xl=x;if(x>xr)xr=x;}}
for(let col=Math.max(0,Math.ceil(xl-0.5));col<=Math.min(D.w-1,Math.ceil(xr-0.5)-1);col++)PIX[r*D.w+col]=c;}}
function degreesAt(t){return D.start+360*(((t%D.period)+D.period)%D.period)/D.period;}
const hash=parseFloat(location.hash.slice(1));
if(D.paused!==null||!isNaN(hash)){frame(degreesAt(isNaN(hash)?D.paused:hash));}
else{const t0=performance.now();const tick=now=>{frame(degreesAt((now-t0)/1000));requestAnimationFrame(tick);};requestAnimationFrame(tick);}
"#;
