#!/bin/sh
# build_types_jar.sh JAVAC JAR LCM_JAR OUT_JAR WORKDIR LCM_FILES...: Java classes of the
# message types, for lcm-spy.
set -e
javac=$1 jar=$2 lcm_jar=$3 out=$4 work=$5
shift 5
rm -rf "$work" && mkdir -p "$work/src" "$work/classes"
lcm-gen --java --jpath "$work/src" "$@"
find "$work/src" -name '*.java' > "$work/sources.txt"
"$javac" -nowarn -cp "$lcm_jar" -d "$work/classes" @"$work/sources.txt"
"$jar" cf "$out" -C "$work/classes" .
