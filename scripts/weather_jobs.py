#!/usr/bin/env python3
"""weather_jobs.py — a `fenestra batch` jobs file with one render per daylight hour of a weather file.

    python3 scripts/weather_jobs.py EPW --days 06-21[,12-21,...] | --from MM-DD --to MM-DD
        --out-dir DIR [--min-altitude 6] [--jobs JOBS.json] -- SCENE [fenestra render options]

Each hour of the chosen days whose sun stands at least --min-altitude degrees high at the middle of
the hour (where the Perez sky is defined for every hour of the shipped year: DESIGN.md §1) and
whose diffuse irradiance is positive becomes a job `MM-DD_HH`: the render options given after `--`,
with `--weather EPW --weather-hour MM-DD:HH --out DIR/MM-DD_HH[.exr]` added (no `.exr` with
`--no-image`). The sun's altitude here is a screening only (the solar declination and equation of
time of Spencer's series, within a few tenths of a degree); fenestra places the sun itself. Writes
the jobs file (standard output without --jobs). Standard library only. Example, the work plane of
the default room every daylight hour of the solstices:

    python3 scripts/weather_jobs.py scenes/weather/tmy_45.000_8.000_2005_2016.epw --days 06-21,12-21 \\
        --out-dir out/solstices --jobs out/solstices.json -- scenes/room.gltf --no-image \\
        --work-plane floor --time 10
    build/fenestra batch out/solstices.json      # out/solstices.summary.csv: each hour's mean lux
"""
import argparse
import datetime
import json
import math
import sys

DAYS = (31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31)


def day_of_year(month, day):
    return sum(DAYS[: month - 1]) + day


def parse_day(text):
    try:
        m, d = (int(v) for v in text.split("-"))
        if not (1 <= m <= 12 and 1 <= d <= DAYS[m - 1]):
            raise ValueError
        return m, d
    except ValueError:
        sys.exit("weather_jobs.py: '%s' is not a day MM-DD" % text)


def altitude_deg(lat, lon, tz, month, day, hour_mid):
    """The sun's altitude (Spencer 1971 declination and equation of time), standard time hour_mid."""
    g = 2 * math.pi * (day_of_year(month, day) - 1) / 365
    decl = (0.006918 - 0.399912 * math.cos(g) + 0.070257 * math.sin(g) - 0.006758 * math.cos(2 * g)
            + 0.000907 * math.sin(2 * g) - 0.002697 * math.cos(3 * g) + 0.00148 * math.sin(3 * g))
    eot_min = 229.18 * (0.000075 + 0.001868 * math.cos(g) - 0.032077 * math.sin(g) - 0.014615 * math.cos(2 * g)
                        - 0.040849 * math.sin(2 * g))
    solar_hour = hour_mid + (4 * (lon - 15 * tz) + eot_min) / 60
    h = math.radians(15 * (solar_hour - 12))
    phi = math.radians(lat)
    s = math.sin(phi) * math.sin(decl) + math.cos(phi) * math.cos(decl) * math.cos(h)
    return math.degrees(math.asin(max(-1.0, min(1.0, s))))


def main():
    argv = sys.argv[1:]
    if "--" not in argv:
        sys.exit("weather_jobs.py: give the render's scene and options after --")
    cut = argv.index("--")
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("epw")
    ap.add_argument("--days", help="MM-DD,MM-DD,...")
    ap.add_argument("--from", dest="first", help="MM-DD: every day from this one ...")
    ap.add_argument("--to", dest="last", help="... to this one (inclusive)")
    ap.add_argument("--out-dir", required=True)
    ap.add_argument("--min-altitude", type=float, default=6.0)
    ap.add_argument("--jobs", help="write the jobs file here (default: standard output)")
    a = ap.parse_args(argv[:cut])
    render = argv[cut + 1:]
    if not render:
        sys.exit("weather_jobs.py: give the render's scene and options after --")
    if any(x in render for x in ("--out", "--weather", "--weather-hour")):
        sys.exit("weather_jobs.py: --out, --weather and --weather-hour are set per job; leave them out")
    if bool(a.days) == bool(a.first or a.last) or bool(a.first) != bool(a.last):
        sys.exit("weather_jobs.py: give --days, or --from and --to")
    if a.days:
        days = [parse_day(t) for t in a.days.split(",")]
    else:
        m0, d0 = parse_day(a.first)
        m1, d1 = parse_day(a.last)
        start, end = datetime.date(2001, m0, d0), datetime.date(2001, m1, d1)
        if end < start:
            sys.exit("weather_jobs.py: --to comes before --from")
        days = [((start + datetime.timedelta(n)).month, (start + datetime.timedelta(n)).day)
                for n in range((end - start).days + 1)]

    with open(a.epw, encoding="latin-1") as f:
        lines = f.read().splitlines()
    loc = lines[0].split(",")
    if loc[0] != "LOCATION" or len(loc) < 9:
        sys.exit("weather_jobs.py: %s: expected the LOCATION line of an EPW file" % a.epw)
    lat, lon, tz = float(loc[6]), float(loc[7]), float(loc[8])
    wanted = set(days)
    no_image = "--no-image" in render
    jobs = []
    for line in lines[8:]:
        f = line.split(",")
        if len(f) < 16:
            continue
        month, day, hour = int(f[1]), int(f[2]), int(f[3])
        if (month, day) not in wanted:
            continue
        dhi = float(f[15])
        if not (0 < dhi < 9999) or altitude_deg(lat, lon, tz, month, day, hour - 0.5) < a.min_altitude:
            continue
        name = "%02d-%02d_%02d" % (month, day, hour)
        out = "%s/%s%s" % (a.out_dir.rstrip("/"), name, "" if no_image else ".exr")
        jobs.append({"name": name, "render": render + ["--weather", a.epw, "--weather-hour",
                                                       "%02d-%02d:%02d" % (month, day, hour), "--out", out]})
    if not jobs:
        sys.exit("weather_jobs.py: no daylight hour on those days")
    text = json.dumps({"jobs": jobs}, indent=1) + "\n"
    if a.jobs:
        with open(a.jobs, "w") as f:
            f.write(text)
        print("weather_jobs.py: %d jobs in %s" % (len(jobs), a.jobs), file=sys.stderr)
    else:
        sys.stdout.write(text)


if __name__ == "__main__":
    main()
