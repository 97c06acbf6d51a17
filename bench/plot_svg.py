"""What bench/'s summary scripts share: the Pareto front of (cost, error) points and an SVG scatter
plot's frame (title, axes, ticks, labels), so that each script only places its own marks."""


def pareto_front(points):
    """Indices of the points no other point dominates (no higher cost and no higher error, and lower in one)."""
    def dominates(q, p):
        return q[0] <= p[0] and q[1] <= p[1] and (q[0] < p[0] or q[1] < p[1])
    return [i for i, p in enumerate(points) if not any(dominates(q, p) for q in points)]


class Plot:
    """An SVG plot of x in [0, 1.05 max] against y over the given values' range; X() and Y() place values."""

    def __init__(self, title, x_label, y_label, xs, ys, x_digits=2, y_digits=4, size=(760, 460), margin=64):
        self.w, self.h = size
        self.m = margin
        self.x0, self.x1 = 0.0, max(xs) * 1.05
        self.y0, self.y1 = min(ys) * 0.95, max(ys) * 1.03
        w, h, m = self.w, self.h, margin
        self.out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" font-family="sans-serif" font-size="11">',
                    f'<rect width="{w}" height="{h}" fill="white"/>',
                    f'<text x="{w/2}" y="20" text-anchor="middle" font-size="13">{title}</text>',
                    f'<line x1="{m}" y1="{h-m}" x2="{w-m}" y2="{h-m}" stroke="black"/>'
                    f'<line x1="{m}" y1="{m}" x2="{m}" y2="{h-m}" stroke="black"/>',
                    f'<text x="{w/2}" y="{h-22}" text-anchor="middle">{x_label}</text>',
                    f'<text x="16" y="{h/2}" transform="rotate(-90 16 {h/2})" text-anchor="middle">{y_label}</text>']
        for k in range(5):
            xv, yv = self.x0 + (self.x1 - self.x0) * k / 4, self.y0 + (self.y1 - self.y0) * k / 4
            self.out.append(f'<text x="{self.X(xv):.0f}" y="{h-m+15}" text-anchor="middle">{xv:.{x_digits}f}</text>')
            self.out.append(f'<text x="{m-5}" y="{self.Y(yv)+4:.0f}" text-anchor="end">{yv:.{y_digits}f}</text>')

    def X(self, x):
        return self.m + (x - self.x0) / (self.x1 - self.x0) * (self.w - 2 * self.m)

    def Y(self, y):
        return self.h - self.m - (y - self.y0) / (self.y1 - self.y0) * (self.h - 2 * self.m)

    def line(self, points, stroke, dash=""):
        self.out.append(f'<polyline fill="none" stroke="{stroke}" stroke-dasharray="{dash}" points="' +
                        " ".join(f"{self.X(x):.1f},{self.Y(y):.1f}" for x, y in sorted(points)) + '"/>')

    def write(self, path, note):
        self.out.append(f'<text x="{self.w-self.m}" y="{self.m-8}" text-anchor="end">{note}</text></svg>')
        path.write_text("\n".join(self.out) + "\n")
