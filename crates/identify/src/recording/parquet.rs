//! Signals as Parquet: a table of one floating-point column per channel, written and read
//! with the file format alone (no arrow arrays), so that a long stream is a file pandas
//! (`pandas.read_parquet`), xarray, Polars and Dask read as it is.
//!
//! **Why Parquet beside CSV.** An hour of caving at 20 kHz is 72 million samples a channel:
//! about 1.5 GB of CSV text a channel, parsed number by number on reading, against about 8
//! bytes a sample in Parquet's column chunks (less where Snappy finds repeats), read at the
//! speed of a copy. The values are stored as written (IEEE doubles, PLAIN encoding), so a
//! signal reads back to the same bits, as the shortest round-trip CSV does.
//!
//! **Layout written.** One REQUIRED DOUBLE column per key, in order; row groups of
//! [`ROWS_PER_GROUP`] samples (Dask and pyarrow read a file by row groups, so a long signal is
//! split into pieces a worker holds); Snappy compression (pyarrow's default codec); the
//! sidecar's JSON under the file's key-value metadata [`METADATA_KEY`], so the file also
//! describes itself where it travels without its sidecar.
//!
//! **Layout read.** Any flat file with the sidecar's columns as DOUBLE, FLOAT, INT32 or INT64
//! (an ADC's counts, signed or unsigned), REQUIRED or OPTIONAL: what pandas, Polars and
//! acquisition software write. An empty (null) value is refused, naming its column and row;
//! so are lists, and integers annotated as decimals, dates or times (their scale or unit
//! would be lost). The footer's row counts are checked against each other and against
//! [`MAX_VALUES`] before any column is decoded.

use super::{error, RecordingError};
use bytes::Bytes;
use parquet::basic::{Compression, ConvertedType, LogicalType, Repetition, Type as PhysicalType};
use parquet::column::reader::{ColumnReader, ColumnReaderImpl};
use parquet::data_type::{DataType, DoubleType};
use parquet::file::metadata::KeyValue;
use parquet::file::properties::WriterProperties;
use parquet::file::reader::{FileReader, SerializedFileReader};
use parquet::file::writer::SerializedFileWriter;
use parquet::schema::types::{ColumnDescriptor, Type};
use std::sync::Arc;

/// The key of the sidecar's JSON in a written file's key-value metadata.
pub const METADATA_KEY: &str = "impact-signal";

/// Samples per row group written: 8 MB a column, a piece a Dask worker reads at once.
pub const ROWS_PER_GROUP: usize = 1 << 20;

/// Most values (samples times columns read) one file may give: 4 GB of doubles, checked
/// from the file's footer before any column is decoded.
pub const MAX_VALUES: u64 = 500_000_000;

/// A Parquet file of the columns `(key, samples)` (every column as long as the first),
/// with `metadata` (the sidecar's JSON) under [`METADATA_KEY`]; its bytes.
pub fn write(columns: &[(&str, &[f64])], metadata: Option<&str>) -> Result<Vec<u8>, RecordingError> {
    let fail = |e: parquet::errors::ParquetError| error("signal.parquet", e.to_string());
    let rows = columns.first().map_or(0, |(_, c)| c.len());
    if let Some((key, c)) = columns.iter().find(|(_, c)| c.len() != rows) {
        return Err(error("signal.parquet", format!("column \"{key}\" has {} samples, the first {rows}", c.len())));
    }
    let fields = columns
        .iter()
        .map(|(key, _)| {
            Type::primitive_type_builder(key, PhysicalType::DOUBLE)
                .with_repetition(Repetition::REQUIRED)
                .build()
                .map(Arc::new)
        })
        .collect::<Result<Vec<_>, _>>()
        .map_err(fail)?;
    let schema = Arc::new(Type::group_type_builder("signal").with_fields(fields).build().map_err(fail)?);
    let properties = WriterProperties::builder()
        .set_compression(Compression::SNAPPY)
        .set_dictionary_enabled(false)
        .set_max_row_group_size(ROWS_PER_GROUP)
        .set_key_value_metadata(metadata.map(|m| vec![KeyValue::new(METADATA_KEY.to_string(), m.to_string())]))
        .build();
    let mut writer = SerializedFileWriter::new(Vec::new(), schema, Arc::new(properties)).map_err(fail)?;
    for start in (0..rows.max(1)).step_by(ROWS_PER_GROUP) {
        let end = (start + ROWS_PER_GROUP).min(rows);
        let mut group = writer.next_row_group().map_err(fail)?;
        for (_, samples) in columns {
            let mut column = group.next_column().map_err(fail)?.ok_or_else(|| fail(missing()))?;
            column.typed::<DoubleType>().write_batch(&samples[start..end], None, None).map_err(fail)?;
            column.close().map_err(fail)?;
        }
        group.close().map_err(fail)?;
    }
    writer.into_inner().map_err(fail)
}

fn missing() -> parquet::errors::ParquetError {
    parquet::errors::ParquetError::General("the schema has fewer columns than given".into())
}

/// The columns `names` of the Parquet file `bytes` (from the file `origin`), in order, as
/// doubles; and the file's own [`METADATA_KEY`] text, if any.
pub fn read(bytes: Vec<u8>, names: &[String], origin: &str) -> Result<(Vec<Vec<f64>>, Option<String>), RecordingError> {
    let fail = |e: parquet::errors::ParquetError| error(origin, format!("not a Parquet file this program reads: {e}"));
    let reader = SerializedFileReader::new(Bytes::from(bytes)).map_err(fail)?;
    let meta = reader.metadata().file_metadata();
    let schema = meta.schema_descr();
    let index: Vec<usize> = names
        .iter()
        .map(|name| {
            let i =
                (0..schema.num_columns()).find(|&i| schema.column(i).path().string() == *name).ok_or_else(|| {
                    let have: Vec<String> =
                        (0..schema.num_columns()).map(|i| schema.column(i).path().string()).collect();
                    error(origin, format!("no column \"{name}\"; the file has {have:?}"))
                })?;
            numeric(&schema.column(i)).map_err(|why| error(origin, format!("column \"{name}\" {why}")))?;
            Ok(i)
        })
        .collect::<Result<_, _>>()?;
    let groups = group_rows(&reader, meta.num_rows(), names.len(), origin)?;
    let text = meta
        .key_value_metadata()
        .and_then(|kv| kv.iter().find(|k| k.key == METADATA_KEY))
        .and_then(|k| k.value.clone());
    let total = groups.iter().sum();
    let mut columns: Vec<Vec<f64>> = names.iter().map(|_| Vec::with_capacity(total)).collect();
    let mut first_row = 0;
    for (g, &rows) in groups.iter().enumerate() {
        let group = reader.get_row_group(g).map_err(fail)?;
        for ((column, &i), name) in columns.iter_mut().zip(&index).zip(names) {
            let before = column.len();
            let descr = schema.column(i);
            let (unsigned, d) = (is_unsigned(&descr), descr.max_def_level());
            let null = match group.get_column_reader(i).map_err(fail)? {
                ColumnReader::DoubleColumnReader(r) => values((r, d), rows, column, |v| v),
                ColumnReader::FloatColumnReader(r) => values((r, d), rows, column, f64::from),
                ColumnReader::Int32ColumnReader(r) if unsigned => values((r, d), rows, column, |v| f64::from(v as u32)),
                ColumnReader::Int32ColumnReader(r) => values((r, d), rows, column, f64::from),
                // Counts beyond 2⁵³ round; no ADC comes near.
                ColumnReader::Int64ColumnReader(r) if unsigned => values((r, d), rows, column, |v| v as u64 as f64),
                ColumnReader::Int64ColumnReader(r) => values((r, d), rows, column, |v| v as f64),
                _ => return Err(error(origin, format!("column \"{name}\" is not numeric"))),
            }
            .map_err(fail)?;
            if let Some(k) = null {
                let row = first_row + k;
                return Err(error(
                    origin,
                    format!("column \"{name}\", row {row}: empty (null); every sample must be given"),
                ));
            }
            if column.len() - before != rows {
                return Err(error(
                    origin,
                    format!("column \"{name}\": row group {g} holds {} of its {rows} rows", column.len() - before),
                ));
            }
            if let Some(k) = (before..column.len()).find(|&k| !column[k].is_finite()) {
                return Err(error(origin, format!("column \"{name}\", row {k}: {} is not a finite number", column[k])));
            }
        }
        first_row += rows;
    }
    Ok((columns, text))
}

/// Why a column is not one this reader takes as samples (None: it is): a flat DOUBLE, FLOAT,
/// INT32 or INT64 column with no annotation but integer width and sign (a decimal's scale, a
/// date's or time's unit would be lost).
fn numeric(c: &ColumnDescriptor) -> Result<(), String> {
    if c.max_rep_level() > 0 {
        return Err("is a list (repeated): give one value a row".into());
    }
    let physical = c.physical_type();
    if !matches!(physical, PhysicalType::DOUBLE | PhysicalType::FLOAT | PhysicalType::INT32 | PhysicalType::INT64) {
        return Err(format!("holds {physical}, not numbers; allowed DOUBLE, FLOAT, INT32, INT64"));
    }
    let plain = matches!(c.logical_type_ref(), None | Some(LogicalType::Integer { .. }))
        && matches!(
            c.converted_type(),
            ConvertedType::NONE
                | ConvertedType::INT_8
                | ConvertedType::INT_16
                | ConvertedType::INT_32
                | ConvertedType::INT_64
                | ConvertedType::UINT_8
                | ConvertedType::UINT_16
                | ConvertedType::UINT_32
                | ConvertedType::UINT_64
        );
    if !plain {
        let what = c.logical_type_ref().map_or_else(|| format!("{}", c.converted_type()), |l| format!("{l:?}"));
        return Err(format!("is annotated {what} (a decimal, date, time or other value, not a plain number)"));
    }
    Ok(())
}

/// Whether an integer column holds unsigned values.
fn is_unsigned(c: &ColumnDescriptor) -> bool {
    matches!(c.logical_type_ref(), Some(LogicalType::Integer { is_signed: false, .. }))
        || matches!(c.converted_type(), ConvertedType::UINT_32 | ConvertedType::UINT_64)
}

/// Every row group's row count, checked against the footer's total and, with the columns
/// read, against [`MAX_VALUES`] before anything is decoded.
fn group_rows(
    reader: &SerializedFileReader<Bytes>,
    footer_rows: i64,
    columns: usize,
    origin: &str,
) -> Result<Vec<usize>, RecordingError> {
    let groups: Vec<i64> = reader.metadata().row_groups().iter().map(|g| g.num_rows()).collect();
    let total = groups.iter().try_fold(0i64, |a, &n| if n < 0 { None } else { a.checked_add(n) });
    if total != Some(footer_rows) {
        return Err(error(
            origin,
            format!("the footer states {footer_rows} rows and its row groups {groups:?}: a damaged file"),
        ));
    }
    let values = (footer_rows as u64).saturating_mul(columns as u64);
    if values > MAX_VALUES {
        return Err(error(
            origin,
            format!("{footer_rows} rows of {columns} columns: {values} values, allowed at most {MAX_VALUES}"),
        ));
    }
    Ok(groups.into_iter().map(|n| n as usize).collect())
}

/// Appends the `rows` values of one column chunk (read by `r`, its largest definition level
/// `max_def`: 0 for a REQUIRED column) to `out`, each through `to_f64`; the first empty (null)
/// row of the chunk, if any (a null's definition level is below the largest; it leaves no
/// value).
fn values<T: DataType>(
    (mut r, max_def): (ColumnReaderImpl<T>, i16),
    rows: usize,
    out: &mut Vec<f64>,
    to_f64: impl Fn(T::T) -> f64,
) -> parquet::errors::Result<Option<usize>>
where
    T::T: Copy,
{
    let (mut buf, mut defs) = (Vec::with_capacity(rows), Vec::with_capacity(rows));
    let mut read = 0;
    while read < rows {
        let (records, _, _) = r.read_records(rows - read, Some(&mut defs), None, &mut buf)?;
        if records == 0 {
            break;
        }
        read += records;
    }
    if max_def > 0 {
        if let Some(k) = defs.iter().position(|&d| d < max_def) {
            return Ok(Some(k));
        }
    }
    out.extend(buf.into_iter().map(to_f64));
    Ok(None)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Doubles read back to the same bits, across row groups, with the metadata.
    #[test]
    fn doubles_round_trip_to_the_bit() {
        let n = ROWS_PER_GROUP + 17;
        let a: Vec<f64> = (0..n).map(|i| (i as f64 * 0.37).sin() * 1e-3 + 1.0 / 3.0).collect();
        let b: Vec<f64> = (0..n).map(|i| -(i as f64).sqrt() * std::f64::consts::PI).collect();
        let bytes = write(&[("time_s", &a), ("a1", &b)], Some("{\"x\": 1}")).unwrap();
        let (cols, meta) = read(bytes, &["a1".into(), "time_s".into()], "t.parquet").unwrap();
        assert_eq!(meta.as_deref(), Some("{\"x\": 1}"));
        assert_eq!((cols[0].len(), cols[1].len()), (n, n));
        assert!(cols[0].iter().zip(&b).all(|(x, y)| x.to_bits() == y.to_bits()));
        assert!(cols[1].iter().zip(&a).all(|(x, y)| x.to_bits() == y.to_bits()));
    }

    /// A file as other writers make it: an optional double, a float, a signed and an
    /// unsigned count, a date; nulls, dates and wide unsigned counts handled by name.
    fn foreign_file() -> Vec<u8> {
        use parquet::basic::LogicalType;
        use parquet::data_type::{FloatType, Int32Type, Int64Type};
        let field = |name: &str, t: PhysicalType, rep: Repetition, logical: Option<LogicalType>| {
            Arc::new(
                Type::primitive_type_builder(name, t).with_repetition(rep).with_logical_type(logical).build().unwrap(),
            )
        };
        let unsigned = Some(LogicalType::Integer { bit_width: 32, is_signed: false });
        let fields = vec![
            field("a", PhysicalType::DOUBLE, Repetition::OPTIONAL, None),
            field("f", PhysicalType::FLOAT, Repetition::REQUIRED, None),
            field("n", PhysicalType::INT64, Repetition::REQUIRED, None),
            field("u", PhysicalType::INT32, Repetition::REQUIRED, unsigned),
            field("day", PhysicalType::INT32, Repetition::REQUIRED, Some(LogicalType::Date)),
        ];
        let schema = Arc::new(Type::group_type_builder("s").with_fields(fields).build().unwrap());
        let mut w =
            SerializedFileWriter::new(Vec::new(), schema, Arc::new(WriterProperties::builder().build())).unwrap();
        let mut g = w.next_row_group().unwrap();
        let mut c = g.next_column().unwrap().unwrap();
        c.typed::<DoubleType>().write_batch(&[1.0, 2.0, 4.0], Some(&[1, 1, 0, 1]), None).unwrap();
        c.close().unwrap();
        let mut c = g.next_column().unwrap().unwrap();
        c.typed::<FloatType>().write_batch(&[0.1, -2.5, 3.0, 1e-3], None, None).unwrap();
        c.close().unwrap();
        let mut c = g.next_column().unwrap().unwrap();
        c.typed::<Int64Type>().write_batch(&[-5, 0, 7, 1 << 40], None, None).unwrap();
        c.close().unwrap();
        let mut c = g.next_column().unwrap().unwrap();
        c.typed::<Int32Type>().write_batch(&[3_000_000_000u32 as i32, 1, 2, 3], None, None).unwrap();
        c.close().unwrap();
        let mut c = g.next_column().unwrap().unwrap();
        c.typed::<Int32Type>().write_batch(&[19000, 19001, 19002, 19003], None, None).unwrap();
        c.close().unwrap();
        g.close().unwrap();
        w.into_inner().unwrap()
    }

    #[test]
    fn foreign_columns_read_as_their_values() {
        let names = ["f", "n", "u"].map(String::from);
        let (cols, meta) = read(foreign_file(), &names, "f.parquet").unwrap();
        assert_eq!(meta, None);
        assert_eq!(cols[0], [0.1f32, -2.5, 3.0, 1e-3].map(f64::from));
        assert_eq!(cols[1], [-5.0, 0.0, 7.0, (1u64 << 40) as f64]);
        assert_eq!(cols[2], [3e9, 1.0, 2.0, 3.0]);
        let null = read(foreign_file(), &["a".into()], "f.parquet").unwrap_err().to_string();
        assert!(null.contains("column \"a\", row 2: empty (null)"), "{null}");
        let date = read(foreign_file(), &["day".into()], "f.parquet").unwrap_err().to_string();
        assert!(date.contains("column \"day\" is annotated Date"), "{date}");
    }

    #[test]
    fn a_missing_column_is_named() {
        let bytes = write(&[("a1", &[1.0, 2.0])], None).unwrap();
        let e = read(bytes, &["a2".into()], "t.parquet").unwrap_err();
        assert!(e.to_string().contains("no column \"a2\"") && e.to_string().contains("a1"), "{e}");
    }

    #[test]
    fn text_is_not_parquet() {
        let e = read(b"time_s,a1\n0,1\n".to_vec(), &["a1".into()], "t.parquet").unwrap_err();
        assert!(e.to_string().starts_with("t.parquet: not a Parquet file"), "{e}");
    }
}
