// The energy-against-time plot: kinetic, potential, elastic and total (J) of every frame, with
// a cursor at the frame shown. A 2D canvas; redrawn only when the frame changes.

const SERIES = [
  { name: 'kinetic', colour: '#e06c60', value: (e) => e[0] },
  { name: 'potential', colour: '#60a0e0', value: (e) => e[1] },
  { name: 'elastic', colour: '#d0b040', value: (e) => e[2] },
  { name: 'total', colour: '#e0e0e0', value: (e) => e[0] + e[1] + e[2] },
];

export class EnergyPlot {
  constructor(canvas, frames) {
    this.canvas = canvas;
    this.frames = frames;
    const all = frames.flatMap((f) => SERIES.map((s) => s.value(f.energy)));
    this.lo = Math.min(...all);
    this.hi = Math.max(...all);
    if (this.hi - this.lo < 1e-12) this.hi = this.lo + 1;
    this.t0 = frames[0].time;
    this.t1 = Math.max(frames[frames.length - 1].time, this.t0 + 1e-9);
  }

  draw(frame) {
    const c = this.canvas.getContext('2d');
    const w = this.canvas.width;
    const h = this.canvas.height;
    const left = 44;
    const bottom = h - 14;
    const x = (t) => left + ((t - this.t0) / (this.t1 - this.t0)) * (w - left - 4);
    const y = (v) => 4 + (1 - (v - this.lo) / (this.hi - this.lo)) * (bottom - 8);
    c.clearRect(0, 0, w, h);
    c.font = '10px system-ui, sans-serif';
    c.fillStyle = '#aaa';
    c.fillText(`${this.hi.toPrecision(3)} J`, 0, 12);
    c.fillText(`${this.lo.toPrecision(3)} J`, 0, bottom);
    c.fillText(`${this.t1.toFixed(2)} s`, w - 34, 12);
    SERIES.forEach((s, k) => {
      c.strokeStyle = s.colour;
      c.beginPath();
      this.frames.forEach((f, i) => (i ? c.lineTo : c.moveTo).call(c, x(f.time), y(s.value(f.energy))));
      c.stroke();
      c.fillStyle = s.colour;
      c.fillText(s.name, left + 4 + k * 52, h - 2);
    });
    c.strokeStyle = '#fff';
    c.beginPath();
    c.moveTo(x(this.frames[frame].time), 0);
    c.lineTo(x(this.frames[frame].time), bottom);
    c.stroke();
  }
}
