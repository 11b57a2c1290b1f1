#!/usr/bin/env bash
# Regenerates the README's gallery: four figures of the default scene, rendered to PNG.
# Needs the release binary and rsvg-convert (Debian: librsvg2-bin). Takes a few minutes (the
# paper studies run the transient yield study).
set -euo pipefail
cd "$(dirname "$0")/../.."
bin=target/release/impact
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
scene() { # a copy of the default scene asking for the given analyses only
    sed -e "/^analyses = \[/,/\]/c analyses = [$1]" scenes/paper-table-1.toml > "$work/$2.toml"
}
scene '"responses", "width-maps"' maps
scene '"transient", "size-map"' dynamic
scene '"paper-studies"' studies
"$bin" compare --scene "$work/maps.toml" --out "$work/maps"
"$bin" dynamic --scene "$work/dynamic.toml" --out "$work/dynamic"
"$bin" compare --scene "$work/studies.toml" --out "$work/studies"
png() { rsvg-convert --zoom 1.5 "$1" -o "docs/gallery/$2.png"; }
png "$work/maps/map-con-1.svg" compliance-ratio-map
png "$work/maps/field-w.svg" deflection-at-pmax
png "$work/dynamic/size-map.svg" transient-over-quasi-static
png "$work/studies/paper-studies/conclusions.svg" conclusions
