#!/usr/bin/env python3
# How well can any associator tell MRCLAM's landmarks apart? With each robot's true pose at
# each landmark sighting (motion capture) and configs/mrclam.yaml's sighting noise (σ 0.15 m,
# 1.2°), the share of sightings whose nearest landmark in Mahalanobis distance is not the one
# the barcode names, and the share with a second landmark inside the 9.21 gate
# (docs/cooperative.md). Usage: scripts/analysis/mrclam_association_oracle.py [DATASET_DIR]
import bisect, math, os, sys
D = (sys.argv[1] if len(sys.argv) > 1 else os.path.join(
    os.path.dirname(__file__), '..', '..', '..', 'shared', 'datasets', 'mrclam',
    'MRCLAM_Dataset6')) + '/'
def load(f): return [list(map(float, l.split())) for l in open(D + f) if l.strip() and not l.startswith('#')]
bar = {int(b): int(s) for s, b in load('Barcodes.dat')}
lm = {int(r[0]): r[1:3] for r in load('Landmark_Groundtruth.dat')}
ids = sorted(lm)
sr, sb = 0.15, math.radians(1.2)
near = [min(math.dist(lm[i], lm[j]) for j in ids if j != i) for i in ids]
print('nearest other landmark [m]: min %.3f median %.3f max %.3f' % (min(near), sorted(near)[len(near) // 2], max(near)))
tot = [0, 0, 0]
for k in range(1, 6):
    gt = load(f'Robot{k}_Groundtruth.dat'); ms = load(f'Robot{k}_Measurement.dat')
    t = [g[0] for g in gt]; c = w = a = 0; rng = []
    for tm, b, r, be in ms:
        sub = bar.get(int(b))
        if sub is None or sub < 6: continue
        i = bisect.bisect_left(t, tm)
        if i <= 0 or i >= len(t) or abs(t[i] - tm) > 0.5: continue
        x, y, th = gt[i][1:4]
        m2 = []
        for j in ids:
            dx, dy = lm[j][0] - x, lm[j][1] - y
            db = (be - (math.atan2(dy, dx) - th) + math.pi) % (2 * math.pi) - math.pi
            m2.append((((r - math.hypot(dx, dy)) / sr) ** 2 + (db / sb) ** 2, j))
        m2.sort(); c += 1; w += m2[0][1] != sub; a += m2[1][0] < 9.21; rng.append(r)
    rng.sort()
    print(f'robot {k}: {c} sightings (median range {rng[len(rng)//2]:.2f} m), nearest is another landmark {100*w/c:.1f} %, a second landmark inside the 9.21 gate {100*a/c:.1f} %')
    tot[0] += c; tot[1] += w; tot[2] += a
print(f'all: {tot[0]} sightings, nearest wrong {100*tot[1]/tot[0]:.1f} %, second inside gate {100*tot[2]/tot[0]:.1f} %')
