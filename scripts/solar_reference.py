#!/usr/bin/env python3
"""solar_reference.py — the reference table for fenestra's solar position (host/sky/solar_position.h).

Computes the sun's position with NREL's SPA (Reda and Andreas 2004) as pvlib implements it
(`pip install pvlib`; nothing in the build or the tests needs it) for 400 places and moments drawn
with a fixed seed (years 1990-2060, latitudes -66..66, any longitude, any time of day, UTC
offsets -12..+14 h), and writes tests/data/solar_position_pvlib.csv: the moment as fenestra reads
it (ISO 8601 with its offset), the place, and SPA's geometric elevation (no refraction) and
azimuth (from north towards east), in degrees. Run: python3 scripts/solar_reference.py
"""
import csv
import datetime as dt
import os
import random

import pandas as pd
import pvlib

rng = random.Random(20261201)
rows = []
for _ in range(400):
    year = rng.randint(1990, 2060)
    start = dt.datetime(year, 1, 1)
    moment = start + dt.timedelta(seconds=rng.randint(0, 365 * 86400 - 1))
    offset_min = rng.choice(range(-12 * 60, 14 * 60 + 1, 30))
    tz = dt.timezone(dt.timedelta(minutes=offset_min))
    local = moment.replace(tzinfo=tz)
    lat = round(rng.uniform(-66.0, 66.0), 4)
    lon = round(rng.uniform(-180.0, 180.0), 4)
    sp = pvlib.solarposition.spa_python(pd.DatetimeIndex([local]), lat, lon, altitude=0,
                                        pressure=101325, temperature=12, delta_t=0.0)
    sign = "+" if offset_min >= 0 else "-"
    iso = local.strftime("%Y-%m-%dT%H:%M:%S") + f"{sign}{abs(offset_min) // 60:02d}:{abs(offset_min) % 60:02d}"
    rows.append([iso, lat, lon, f"{float(sp['elevation'].iloc[0]):.6f}", f"{float(sp['azimuth'].iloc[0]):.6f}",
                 f"{float(sp['apparent_elevation'].iloc[0]):.6f}"])

out = os.path.join(os.path.dirname(__file__), "..", "tests", "data", "solar_position_pvlib.csv")
with open(out, "w", newline="") as f:
    w = csv.writer(f)
    w.writerow(["time", "latitude_deg", "longitude_deg", "elevation_deg", "azimuth_deg", "apparent_elevation_deg"])
    w.writerows(rows)
print(f"wrote {len(rows)} rows to {os.path.normpath(out)} (pvlib {pvlib.__version__}, SPA, delta_t 0)")
