#!/usr/bin/env python3
"""Held-out synthetic shapes for the remesh and codec bars (issue "remesher on every mesh").

Writes fifteen ASCII PLY meshes into OUT_DIR (default /tmp/eqmesh_heldout_shapes): machined
shapes (a gridded box, a 24-tooth gear, a washer, a two-ring cylinder, a needle), thin and flat
ones (a 1 x 1 x 0.02 plate, a flat disc, a long thin cylinder, an open tube), an open height
field, a noisy sphere, scattered parts (40 icospheres, 300 cubes, 100 small spheres) and an
icosahedron. No bench lists them; run them through copies of bench/midsize_remesh.sh and
bench/midsize_codec.sh with the mesh list replaced (bench/log/2026-12-06-crease-curves.md).
Plain Python, deterministic (fixed seeds).
"""
import math
import os
import random
import sys

OUT = sys.argv[1] if len(sys.argv) > 1 else "/tmp/eqmesh_heldout_shapes"


def write(name, V, F):
    os.makedirs(OUT, exist_ok=True)
    with open(os.path.join(OUT, name + ".ply"), "w") as f:
        f.write("ply\nformat ascii 1.0\nelement vertex %d\nproperty float x\nproperty float y\nproperty float z\n"
                "element face %d\nproperty list uchar int vertex_indices\nend_header\n" % (len(V), len(F)))
        for v in V:
            f.write("%.7g %.7g %.7g\n" % v)
        for t in F:
            f.write("3 %d %d %d\n" % t)

random.seed(7)
def grid(nu,nv,fn,closed_u=False):
    V=[];F=[]
    cu = nu if closed_u else nu+1
    for j in range(nv+1):
        for i in range(cu): V.append(fn(i/nu,j/nv))
    for j in range(nv):
        for i in range(nu):
            a=j*cu+i; b=j*cu+(i+1)%cu; c=(j+1)*cu+i; d=(j+1)*cu+(i+1)%cu
            F.append((a,b,d)); F.append((a,d,c))
    return V,F
def append(V,F,V2,F2):
    o=len(V); V+=V2; F+=[(a+o,b+o,c+o) for a,b,c in F2]
# terrain: open height field
V,F=grid(119,119,lambda u,v:(u,v,0.15*math.sin(6*u)*math.cos(5*v)+0.05*math.sin(23*u+3*v)+0.004*(random.random()-0.5)))
write("terrain",V,F)
# flat disc (planar, one boundary): a polar grid
def disc(nr,na):
    V=[(0,0,0)];F=[]
    for r in range(1,nr+1):
        for a in range(na): V.append((r/nr*math.cos(2*math.pi*a/na), r/nr*math.sin(2*math.pi*a/na),0))
    for a in range(na): F.append((0,1+a,1+(a+1)%na))
    for r in range(1,nr):
        for a in range(na):
            p=1+(r-1)*na; q=1+r*na
            F.append((p+a,q+a,q+(a+1)%na)); F.append((p+a,q+(a+1)%na,p+(a+1)%na))
    return V,F
V,F=disc(40,120); write("flat_disc",V,F)
# box surface (closed) of size sx,sy,sz with n cells per unit
def box(sx,sy,sz,n):
    V=[];F=[];idx={}
    def vid(p):
        k=tuple(round(c*1e6) for c in p)
        if k not in idx: idx[k]=len(V); V.append(p)
        return idx[k]
    faces=[((0,0,0),(sx,0,0),(0,sy,0)),((0,0,sz),(0,sy,0),(sx,0,0)),
           ((0,0,0),(0,sy,0),(0,0,sz)),((sx,0,0),(0,0,sz),(0,sy,0)),
           ((0,0,0),(0,0,sz),(sx,0,0)),((0,sy,0),(sx,0,0),(0,0,sz))]
    for o,a,b in faces:
        na=max(1,int(round(max(a)*n))); nb=max(1,int(round(max(b)*n)))
        for j in range(nb):
            for i in range(na):
                def P(ii,jj): return vid(tuple(o[k]+a[k]*ii/na+b[k]*jj/nb for k in range(3)))
                A,B,C,D=P(i,j),P(i+1,j),P(i,j+1),P(i+1,j+1)
                F.append((A,B,D));F.append((A,D,C))
    return V,F
V,F=box(1,1,0.02,50); write("thin_plate",V,F)
V,F=box(1,0.6,0.4,30); write("box_fine",V,F)
# long thin closed cylinder
def cyl(r,L,na,nl,caps=True):
    V,F=grid(na,nl,lambda u,v:(r*math.cos(2*math.pi*u),r*math.sin(2*math.pi*u),L*v),closed_u=True)
    if caps:
        c0=len(V);V.append((0,0,0));c1=len(V);V.append((0,0,L))
        for i in range(na):
            F.append((c0,(i+1)%na,i)); F.append((c1,nl*na+i,nl*na+(i+1)%na))
    return V,F
V,F=cyl(0.02,2,48,500); write("long_cylinder",V,F)
V,F=cyl(0.3,1,60,60,caps=False); write("open_tube",V,F)
# icosphere
def ico(sub):
    t=(1+5**0.5)/2
    V=[(-1,t,0),(1,t,0),(-1,-t,0),(1,-t,0),(0,-1,t),(0,1,t),(0,-1,-t),(0,1,-t),(t,0,-1),(t,0,1),(-t,0,-1),(-t,0,1)]
    F=[(0,11,5),(0,5,1),(0,1,7),(0,7,10),(0,10,11),(1,5,9),(5,11,4),(11,10,2),(10,7,6),(7,1,8),(3,9,4),(3,4,2),(3,2,6),(3,6,8),(3,8,9),(4,9,5),(2,4,11),(6,2,10),(8,6,7),(9,8,1)]
    V=[tuple(c/math.sqrt(sum(x*x for x in v)) for c in v) for v in V]
    for _ in range(sub):
        mid={};F2=[]
        def m(a,b):
            k=(min(a,b),max(a,b))
            if k not in mid:
                p=[(V[a][i]+V[b][i])/2 for i in range(3)];n=math.sqrt(sum(x*x for x in p))
                mid[k]=len(V);V.append(tuple(x/n for x in p))
            return mid[k]
        for a,b,c in F:
            ab,bc,ca=m(a,b),m(b,c),m(c,a); F2+=[(a,ab,ca),(b,bc,ab),(c,ca,bc),(ab,bc,ca)]
        F=F2
    return V,F
V,F=ico(0); write("icosahedron",V,F)
Vs,Fs=[],[]
for k in range(40):
    v,f=ico(2); c=(random.uniform(0,10),random.uniform(0,10),random.uniform(0,10)); s=random.uniform(0.2,0.6)
    append(Vs,Fs,[(c[0]+s*x,c[1]+s*y,c[2]+s*z) for x,y,z in v],f)
write("many_spheres",Vs,Fs)
# noisy sphere (scan-like)
v,f=ico(5); V=[]
for x,y,z in v:
    r=1+0.05*math.sin(7*x)*math.sin(5*y)+0.003*random.gauss(0,1); V.append((r*x,r*y,r*z))
write("noisy_sphere",V,f)
# gear: extruded toothed polygon, closed, sharp 90-degree creases
def gear(teeth,r0,r1,hgt,nz):
    prof=[]
    for t in range(teeth):
        for k,(rr,fr) in enumerate([(r0,0),(r1,0.1),(r1,0.4),(r0,0.5)]):
            a=2*math.pi*(t+fr)/teeth; prof.append((rr*math.cos(a),rr*math.sin(a)))
    n=len(prof);V=[];F=[]
    for j in range(nz+1):
        for x,y in prof: V.append((x,y,hgt*j/nz))
    for j in range(nz):
        for i in range(n):
            a=j*n+i;b=j*n+(i+1)%n;c=a+n;d=b+n;F.append((a,b,d));F.append((a,d,c))
    for z,flip in ((0,True),(nz,False)):
        c=len(V);V.append((0,0,hgt*z/nz))
        for i in range(n):
            a=z*n+i;b=z*n+(i+1)%n
            F.append((c,b,a) if flip else (c,a,b))
    return V,F
V,F=gear(24,1,1.2,0.3,6); write("gear",V,F)

# washer: annulus extruded, rings of k points
def washer(r0,r1,h,k,nz):
    V=[];F=[]
    def ring(r,z): return [(r*math.cos(2*math.pi*i/k), r*math.sin(2*math.pi*i/k), z) for i in range(k)]
    # outer wall rings 0..nz, inner wall rings
    outer=[];inner=[]
    for j in range(nz+1):
        outer.append(len(V)); V+=ring(r1,h*j/nz)
    for j in range(nz+1):
        inner.append(len(V)); V+=ring(r0,h*j/nz)
    for j in range(nz):
        for i in range(k):
            a=outer[j]+i;b=outer[j]+(i+1)%k;c=outer[j+1]+i;d=outer[j+1]+(i+1)%k
            F.append((a,b,d));F.append((a,d,c))
            a=inner[j]+i;b=inner[j]+(i+1)%k;c=inner[j+1]+i;d=inner[j+1]+(i+1)%k
            F.append((a,d,b));F.append((a,c,d))
    for (o,ii,top) in ((outer[0],inner[0],False),(outer[nz],inner[nz],True)):
        for i in range(k):
            a=o+i;b=o+(i+1)%k;c=ii+i;d=ii+(i+1)%k
            if top: F.append((a,b,d));F.append((a,d,c))
            else: F.append((a,d,b));F.append((a,c,d))
    return V,F
V,F=washer(0.5,1.0,0.3,64,4); write("washer",V,F)
# skinny cylinder: 2 rings, tall skinny triangles, 96 around, capped
k=96;V=[];F=[]
for j in range(2):
    for i in range(k): V.append((math.cos(2*math.pi*i/k),math.sin(2*math.pi*i/k),3.0*j))
for i in range(k):
    a=i;b=(i+1)%k;c=k+i;d=k+(i+1)%k;F.append((a,b,d));F.append((a,d,c))
c0=len(V);V.append((0,0,0));c1=len(V);V.append((0,0,3.0))
for i in range(k): F.append((c0,(i+1)%k,i));F.append((c1,k+i,k+(i+1)%k))
write("skinny_cylinder",V,F)
# needle: cone with a long thin tip over a disc base
k=48;rings=60;V=[];F=[]
for j in range(rings):
    t=j/(rings-1); r=0.3*(1-t)**1.0+0.0; z=4.0*t
    if j==rings-1: break
    for i in range(k): V.append((r*math.cos(2*math.pi*i/k),r*math.sin(2*math.pi*i/k),z))
R=rings-1
for j in range(R-1):
    for i in range(k):
        a=j*k+i;b=j*k+(i+1)%k;c=(j+1)*k+i;d=(j+1)*k+(i+1)%k;F.append((a,b,d));F.append((a,d,c))
tip=len(V);V.append((0,0,4.0));base=len(V);V.append((0,0,0))
for i in range(k):
    F.append(((R-1)*k+i,(R-1)*k+(i+1)%k,tip)); F.append((base,(i+1)%k,i))
write("needle",V,F)

random.seed(3)
def cube(o,s):
    V=[(o[0]+s*x,o[1]+s*y,o[2]+s*z) for x in (0,1) for y in (0,1) for z in (0,1)]
    # vertices index = x*4+y*2+z
    Q=[(0,1,3,2),(4,6,7,5),(0,4,5,1),(2,3,7,6),(0,2,6,4),(1,5,7,3)]
    F=[]
    for a,b,c,d in Q: F+= [(a,b,c),(a,c,d)]
    return V,F
V=[];F=[]
for i in range(300):
    v,f=cube((random.uniform(0,20),random.uniform(0,20),random.uniform(0,20)),random.uniform(0.3,1.0))
    o=len(V); V+=v; F+=[(a+o,b+o,c+o) for a,b,c in f]
write("cubes300",V,F)
# icosphere(1) grid: 42 vertices each
V=[];F=[]
v0,f0=ico(1)
for i in range(10):
    for j in range(10):
        o=len(V); V+=[(x*0.4+i,y*0.4+j,z*0.4) for x,y,z in v0]; F+=[(a+o,b+o,c+o) for a,b,c in f0]
write("balls100",V,F)

print("wrote 15 shapes to", OUT)
