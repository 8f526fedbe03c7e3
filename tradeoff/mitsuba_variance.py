#!/usr/bin/env python3
"""mitsuba_variance.py -- Mitsuba 3's noise per sample, and what each of its dimensions'
stratification buys, on the reference scenes of ../shared/baselines/mitsuba3/render.py
(tradeoff/7-variance.sh; docs/BENCHMARKS.md, Noise per sample).  Needs Mitsuba 3 with numpy
(an optional baseline, as pbrt-v2; never needed by make check).

    mitsuba_variance.py RENDER_PY SCENE SPP [--seeds A B] [--variant llvm_ad_rgb]
                        LABEL=[OPTION,...] ...

For each LABEL the scene is rendered with seeds A and B (1, 2) and one line "LABEL rmse mean
seconds" is printed, as tradeoff/variance prints it for materia: rmse = sqrt(mean (a - b)^2 / 2)
over pixels and colour channels, one render's error without a reference.

The integrator is Mitsuba 3.9's "path" (src/integrators/path.cpp) re-written here in Python,
drawing its numbers from an "ldsampler" of its own beside an "independent" one, so that single
dimensions can be switched; the empty option list reproduces the plugin's noise (checked against
Mitsuba's own "path" by OPTION builtin).  Per path vertex Mitsuba draws: the emitter sample (2D;
its first value also picks the emitter and is rescaled, Scene::sample_emitter), the BSDF's
component (1D) and direction (2D), Russian roulette (1D).  OPTIONs:
    builtin            Mitsuba's own "path" plugin and its sampler ("ldsampler" unless
                       independent is given too)
    independent        every value independent (the "independent" sampler)
    image              the image position independent (the film's sampler is "independent")
    NAME[@DEPTH]       one dimension independent, at every vertex or at vertex DEPTH
                       (0 = the camera ray's hit): emitter, bsdf1 (component), bsdf2
                       (direction), rr
    choice             the emitter chosen by a 1D number of its own (pbrt-v2's
                       UniformSampleOneLight) instead of the emitter sample's first value
    rr=pbrt            pbrt-v2's roulette: after the fourth vertex, continuation probability
                       min(0.5, luminance of the throughput)
"""
import argparse
import importlib.util
import sys
import time


def load_render_py(path):
    spec = importlib.util.spec_from_file_location('mitsuba_scene', path)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('render_py')
    ap.add_argument('scene')
    ap.add_argument('spp', type=int)
    ap.add_argument('configs', nargs='+')
    ap.add_argument('--seeds', type=int, nargs=2, default=[1, 2])
    ap.add_argument('--variant', default='llvm_ad_rgb')
    ap.add_argument('--threads', type=int, default=2)
    a = ap.parse_args()
    scenes = load_render_py(a.render_py)
    scenes.find_libllvm()
    import numpy as np
    import drjit as dr
    import mitsuba as mi
    mi.set_variant(a.variant)
    dr.set_thread_count(a.threads)
    max_depth = scenes.SCENES[a.scene]['pbrt_maxdepth'] + 2

    def mis(p, q):
        p2, q2 = p * p, q * q
        return dr.select(p2 + q2 > 0, p2 / (p2 + q2), 0)

    class Path(mi.SamplingIntegrator):
        """Mitsuba's path integrator (path.cpp), one vertex per loop iteration, unrolled."""

        def __init__(self, props, opts, seed):
            super().__init__(props)
            self.opts, self.seed = opts, seed

        def sample(self, scene, sampler, ray, medium=None, active=True):
            o = self.opts
            n = dr.width(ray.o.x)
            gens = []
            for kind, salt in (('ldsampler', 7919), ('independent', 104729)):
                s = mi.load_dict({'type': kind, 'sample_count': a.spp})
                s.set_samples_per_wavefront(a.spp)
                s.seed(self.seed * 1000003 + salt, n)
                gens.append(s)
            ld, ind = gens

            def indep(name, depth):
                return 'independent' in o or name in o or ('%s@%d' % (name, depth)) in o

            def d1(name, depth):
                x, y = ld.next_1d(), ind.next_1d()
                return y if indep(name, depth) else x

            def d2(name, depth):
                x, y = ld.next_2d(), ind.next_2d()
                return y if indep(name, depth) else x

            ctx = mi.BSDFContext()
            nem = len(scene.emitters())
            ray = mi.Ray3f(ray)
            thr, res, eta = mi.Spectrum(1.0), mi.Spectrum(0.0), mi.Float(1.0)
            active = mi.Bool(active)
            prev_si = dr.zeros(mi.Interaction3f)
            prev_pdf, prev_delta, valid = mi.Float(1.0), mi.Bool(True), mi.Bool(False)
            for depth in range(max_depth):
                si = scene.ray_intersect(ray, active)
                # emission found by the previous vertex's BSDF sample, MIS-weighted
                ds = mi.DirectionSample3f(scene, si, prev_si)
                em_pdf = scene.pdf_emitter_direction(prev_si, ds, active & ~prev_delta)
                res[active] += thr * ds.emitter.eval(si, active & (prev_pdf > 0)) * mis(prev_pdf, em_pdf)
                valid |= active & si.is_valid()
                active_next = active & (depth + 1 < max_depth) & si.is_valid()
                bsdf = si.bsdf(ray)
                active_em = active_next & mi.has_flag(bsdf.flags(), mi.BSDFFlags.Smooth)
                u_em = d2('emitter', depth)
                if 'choice' in o:
                    u_choice = d1('choice', depth)
                    idx = dr.minimum(mi.UInt32(u_choice * nem), nem - 1)
                    em = dr.gather(mi.EmitterPtr, scene.emitters_dr(), idx, active_em)
                    ds_e, em_w = em.sample_direction(si, u_em, active_em)
                    occluded = scene.ray_test(si.spawn_ray_to(ds_e.p), active_em)
                    em_w = dr.select(occluded | (ds_e.pdf == 0), 0, em_w * nem)
                    ds_e.pdf /= nem
                else:
                    ds_e, em_w = scene.sample_emitter_direction(si, u_em, True, active_em)
                active_em &= ds_e.pdf != 0
                wo = si.to_local(ds_e.d)
                s1, s2 = d1('bsdf1', depth), d2('bsdf2', depth)
                bval, bpdf, bs, bw = bsdf.eval_pdf_sample(ctx, si, wo, s1, s2, active_next)
                res[active_em] += thr * bval * em_w * dr.select(ds_e.delta, 1.0, mis(ds_e.pdf, bpdf))
                ray = si.spawn_ray(si.to_world(bs.wo))
                thr *= bw
                eta *= bs.eta
                prev_si, prev_pdf = mi.Interaction3f(si), bs.pdf
                prev_delta = mi.has_flag(bs.sampled_type, mi.BSDFFlags.Delta)
                tmax = dr.max(thr)
                u_rr = d1('rr', depth)
                if 'rr=pbrt' in o:
                    q, rr_on = dr.minimum(mi.luminance(thr), 0.5), depth > 3
                else:
                    q, rr_on = dr.minimum(tmax * eta * eta, 0.95), depth + 1 >= 5
                if rr_on:
                    thr *= dr.rcp(q)
                    active = active_next & (u_rr < q) & (tmax != 0)
                else:
                    active = active_next & (tmax != 0)
            return res, valid, []

    for cfg in a.configs:
        label, _, spec = cfg.partition('=')
        opts = set(x for x in spec.split(',') if x)
        images, t0 = [], time.time()
        for seed in a.seeds:
            film_sampler = 'independent' if ('image' in opts or 'independent' in opts) else 'ldsampler'
            d = scenes.scene_dict(mi, a.scene, a.spp, max_depth, film_sampler, 'blend')
            if 'builtin' not in opts:
                mi.register_integrator('pathswitch', lambda props, o=opts, s=seed: Path(props, o, s))
                d['integrator'] = {'type': 'pathswitch'}
            sc = mi.load_dict(d)
            images.append(np.array(mi.render(sc, spp=a.spp, seed=seed), dtype=np.float64)[:, :, :3])
        diff = images[0] - images[1]
        print('%s %.6g %.6g %.2f' % (label, np.sqrt((diff * diff).mean() / 2),
                                     (images[0].mean() + images[1].mean()) / 2, time.time() - t0))
        sys.stdout.flush()


if __name__ == '__main__':
    main()
