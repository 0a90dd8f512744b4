//! CSV records written by serde straight into one reused buffer: the bytes
//! `csv::Writer::serialize` writes for the same value (its default settings, `\n` between
//! records), without its per-field pass.
//!
//! The fields are what the value's `Serialize` gives, in its order, flattened as the csv crate
//! flattens them (a struct's fields, a tuple's elements, `None` as an empty field, a unit
//! variant as its name); so every column still comes from a typed field. Integers go through
//! itoa, as in the csv crate; doubles through zmij, which writes ryu's shortest text (the csv
//! crate's) in half ryu's instructions, its one difference (the sign of a positive exponent)
//! taken out. Numbers are written into the buffer with no quoting pass, since no number needs
//! quotes; text is quoted by csv_core's own rule ([`csv_core::Writer::should_quote`],
//! [`csv_core::quote`]). A sweep's row has twenty-odd doubles, and this is what writing them
//! costs: the formatting, nothing around it.

use std::fmt::Display;
use std::sync::LazyLock;

use serde::Serialize;
use serde::ser::{self, Impossible};
use thiserror::Error;

/// A value that has no CSV record form (a map, an enum variant with fields), or records of
/// different widths.
#[derive(Debug, Error)]
#[error("writing CSV: {0}")]
pub struct RecordError(String);

impl ser::Error for RecordError {
    fn custom<T: Display>(msg: T) -> Self {
        RecordError(msg.to_string())
    }
}

impl From<RecordError> for std::io::Error {
    fn from(e: RecordError) -> Self {
        std::io::Error::other(e)
    }
}

/// csv_core's writer with the csv crate's default settings: asked only which text needs
/// quotes.
static QUOTING: LazyLock<csv_core::Writer> =
    LazyLock::new(|| csv_core::WriterBuilder::new().build());

/// CSV records appended to one buffer.
pub struct CsvRecords {
    bytes: Vec<u8>,
    /// The `\n` bytes written: one per record, and those inside quoted text.
    lines: usize,
    /// Records written.
    records: usize,
    /// The fields of the first record: every record must have as many (as the csv crate's
    /// writer requires, unless made flexible).
    width: Option<usize>,
}

impl Default for CsvRecords {
    fn default() -> Self {
        CsvRecords::with_capacity(0)
    }
}

impl CsvRecords {
    /// An empty buffer with room for `bytes`.
    pub fn with_capacity(bytes: usize) -> CsvRecords {
        CsvRecords {
            bytes: Vec::with_capacity(bytes),
            lines: 0,
            records: 0,
            width: None,
        }
    }

    /// Append `record` as one CSV record. On an error nothing of it is kept.
    pub fn push<T: Serialize + ?Sized>(&mut self, record: &T) -> Result<(), RecordError> {
        let start = self.bytes.len();
        let mut fields = Fields::new(&mut self.bytes, false);
        let written = record.serialize(&mut fields);
        let (count, newlines) = (fields.count, fields.newlines);
        let width = *self.width.get_or_insert(count);
        let written = written.and_then(|()| {
            if count == width {
                Ok(())
            } else {
                Err(RecordError(format!(
                    "found record with {count} fields, but the previous record has {width} fields"
                )))
            }
        });
        if let Err(e) = written {
            self.bytes.truncate(start);
            if self.records == 0 {
                self.width = None;
            }
            return Err(e);
        }
        // A record with no bytes (one empty field) is written as an empty quoted field, so
        // that it is not read as no record at all.
        if self.bytes.len() == start {
            self.bytes.extend_from_slice(b"\"\"");
        }
        self.bytes.push(b'\n');
        self.lines += newlines + 1;
        self.records += 1;
        Ok(())
    }

    /// The bytes so far.
    pub fn as_bytes(&self) -> &[u8] {
        &self.bytes
    }

    /// The bytes, the buffer given up.
    pub fn into_bytes(self) -> Vec<u8> {
        self.bytes
    }

    /// The lines the bytes hold (a record whose text holds a line break takes more than one).
    pub fn lines(&self) -> usize {
        self.lines
    }

    /// The records held.
    pub fn records(&self) -> usize {
        self.records
    }
}

/// The CSV header of a record of type `T` as the csv crate writes it before `record` (its
/// field names; a flattened map's keys, as a nested struct's fields, are the names of the
/// fields they write), with its line end; empty for a value without field names (a tuple).
pub fn header_of<T: Serialize + ?Sized>(record: &T) -> Result<Vec<u8>, RecordError> {
    let mut bytes = Vec::new();
    let mut fields = Fields::new(&mut bytes, true);
    record.serialize(&mut fields)?;
    if fields.unnamed || fields.count == 0 {
        return Ok(Vec::new());
    }
    bytes.push(b'\n');
    Ok(bytes)
}

/// The serialiser of one record: each scalar a field.
struct Fields<'a> {
    out: &'a mut Vec<u8>,
    quoting: &'a csv_core::Writer,
    /// Fields written so far.
    count: usize,
    /// `\n` bytes inside quoted text.
    newlines: usize,
    /// Writing the header: each scalar writes the name it is written under, not its value.
    header: bool,
    /// The name of the field being written (a struct's field, a map's key).
    key: Option<String>,
    /// In a header, a scalar met without a name (a tuple's element): the record has no header.
    unnamed: bool,
}

impl Fields<'_> {
    /// A record's serialiser writing into `out`: its header when `header`, else its fields.
    fn new(out: &mut Vec<u8>, header: bool) -> Fields<'_> {
        Fields {
            out,
            quoting: &QUOTING,
            count: 0,
            newlines: 0,
            header,
            key: None,
            unnamed: false,
        }
    }

    /// Start a field: a delimiter before every field but the first.
    fn next(&mut self) {
        if self.count > 0 {
            self.out.push(b',');
        }
        self.count += 1;
    }

    /// A field that never needs quotes (a number, an empty field).
    fn bare(&mut self, text: &[u8]) -> Result<(), RecordError> {
        if self.header {
            return self.name();
        }
        self.next();
        self.out.extend_from_slice(text);
        Ok(())
    }

    /// In a header, the name of the scalar being written.
    fn name(&mut self) -> Result<(), RecordError> {
        match self.key.take() {
            Some(key) => {
                self.header = false;
                let written = self.text(key.as_bytes());
                self.header = true;
                written
            }
            None => {
                self.unnamed = true;
                self.next();
                Ok(())
            }
        }
    }

    /// A text field, quoted where csv quotes it.
    fn text(&mut self, text: &[u8]) -> Result<(), RecordError> {
        if self.header {
            return self.name();
        }
        self.next();
        if !self.quoting.should_quote(text) {
            self.out.extend_from_slice(text);
            return Ok(());
        }
        self.newlines += text.iter().filter(|&&b| b == b'\n').count();
        self.out.push(b'"');
        let mut input = text;
        while !input.is_empty() {
            // Every quote doubled: at most twice the input.
            let at = self.out.len();
            self.out.resize(at + 2 * input.len(), 0);
            let (_, read, wrote) = csv_core::quote(input, &mut self.out[at..], b'"', b'\\', true);
            self.out.truncate(at + wrote);
            input = &input[read..];
        }
        self.out.push(b'"');
        Ok(())
    }
}

macro_rules! integers {
    ($($method:ident: $t:ty),*) => {$(
        fn $method(self, v: $t) -> Result<(), RecordError> {
            self.bare(itoa::Buffer::new().format(v).as_bytes())
        }
    )*};
}

impl ser::Serializer for &mut Fields<'_> {
    type Ok = ();
    type Error = RecordError;
    type SerializeSeq = Self;
    type SerializeTuple = Self;
    type SerializeTupleStruct = Self;
    type SerializeTupleVariant = Impossible<(), RecordError>;
    type SerializeMap = Self;
    type SerializeStruct = Self;
    type SerializeStructVariant = Impossible<(), RecordError>;

    fn serialize_bool(self, v: bool) -> Result<(), RecordError> {
        self.bare(if v { b"true" } else { b"false" })
    }

    integers!(
        serialize_i8: i8, serialize_i16: i16, serialize_i32: i32, serialize_i64: i64,
        serialize_i128: i128, serialize_u8: u8, serialize_u16: u16, serialize_u32: u32,
        serialize_u64: u64, serialize_u128: u128
    );

    fn serialize_f32(self, v: f32) -> Result<(), RecordError> {
        self.bare(ryu::Buffer::new().format(v).as_bytes())
    }

    fn serialize_f64(self, v: f64) -> Result<(), RecordError> {
        if self.header {
            return self.name();
        }
        let mut buffer = zmij::Buffer::new();
        let text = buffer.format(v).as_bytes();
        // zmij writes ryu's digits and ryu's choice of plain or exponent form, but a positive
        // exponent with its sign (`1e+16` where ryu, and so the csv crate, write `1e16`); a
        // sign only a number of magnitude 1e16 or more can have.
        match (v.abs() >= 1e16)
            .then(|| text.iter().position(|&b| b == b'+'))
            .flatten()
        {
            Some(sign) => {
                self.next();
                self.out.extend_from_slice(&text[..sign]);
                self.out.extend_from_slice(&text[sign + 1..]);
                Ok(())
            }
            None => self.bare(text),
        }
    }

    fn serialize_char(self, v: char) -> Result<(), RecordError> {
        self.text(v.encode_utf8(&mut [0; 4]).as_bytes())
    }

    fn serialize_str(self, v: &str) -> Result<(), RecordError> {
        self.text(v.as_bytes())
    }

    fn serialize_bytes(self, v: &[u8]) -> Result<(), RecordError> {
        self.text(v)
    }

    fn serialize_none(self) -> Result<(), RecordError> {
        self.bare(b"")
    }

    fn serialize_some<T: Serialize + ?Sized>(self, value: &T) -> Result<(), RecordError> {
        value.serialize(self)
    }

    fn serialize_unit(self) -> Result<(), RecordError> {
        self.bare(b"")
    }

    fn serialize_unit_struct(self, name: &'static str) -> Result<(), RecordError> {
        self.text(name.as_bytes())
    }

    fn serialize_unit_variant(
        self,
        _name: &'static str,
        _index: u32,
        variant: &'static str,
    ) -> Result<(), RecordError> {
        self.text(variant.as_bytes())
    }

    fn serialize_newtype_struct<T: Serialize + ?Sized>(
        self,
        _name: &'static str,
        value: &T,
    ) -> Result<(), RecordError> {
        value.serialize(self)
    }

    fn serialize_newtype_variant<T: Serialize + ?Sized>(
        self,
        _name: &'static str,
        _index: u32,
        _variant: &'static str,
        value: &T,
    ) -> Result<(), RecordError> {
        value.serialize(self)
    }

    fn serialize_seq(self, _len: Option<usize>) -> Result<Self, RecordError> {
        Ok(self)
    }

    fn serialize_tuple(self, _len: usize) -> Result<Self, RecordError> {
        Ok(self)
    }

    fn serialize_tuple_struct(self, _name: &'static str, _len: usize) -> Result<Self, RecordError> {
        Ok(self)
    }

    fn serialize_tuple_variant(
        self,
        _name: &'static str,
        _index: u32,
        _variant: &'static str,
        _len: usize,
    ) -> Result<Self::SerializeTupleVariant, RecordError> {
        Err(ser::Error::custom(
            "serializing enum tuple variants is not supported",
        ))
    }

    fn serialize_map(self, _len: Option<usize>) -> Result<Self, RecordError> {
        Ok(self)
    }

    fn serialize_struct(self, _name: &'static str, _len: usize) -> Result<Self, RecordError> {
        Ok(self)
    }

    fn serialize_struct_variant(
        self,
        _name: &'static str,
        _index: u32,
        _variant: &'static str,
        _len: usize,
    ) -> Result<Self::SerializeStructVariant, RecordError> {
        Err(ser::Error::custom(
            "serializing enum struct variants is not supported",
        ))
    }
}

/// The compounds whose parts are fields in turn: a sequence's, a tuple's elements.
macro_rules! compounds {
    ($($compound:ident::$method:ident),*) => {$(
        impl ser::$compound for &mut Fields<'_> {
            type Ok = ();
            type Error = RecordError;

            fn $method<T: Serialize + ?Sized>(&mut self, value: &T) -> Result<(), RecordError> {
                value.serialize(&mut **self)
            }

            fn end(self) -> Result<(), RecordError> {
                Ok(())
            }
        }
    )*};
}

compounds!(
    SerializeSeq::serialize_element,
    SerializeTuple::serialize_element,
    SerializeTupleStruct::serialize_field
);

impl ser::SerializeMap for &mut Fields<'_> {
    type Ok = ();
    type Error = RecordError;

    fn serialize_key<T: Serialize + ?Sized>(&mut self, key: &T) -> Result<(), RecordError> {
        if self.header {
            self.key = Some(match serde_json::to_value(key) {
                Ok(serde_json::Value::String(name)) => name,
                _ => return Err(ser::Error::custom("a map's key must be text")),
            });
        }
        Ok(())
    }

    fn serialize_value<T: Serialize + ?Sized>(&mut self, value: &T) -> Result<(), RecordError> {
        value.serialize(&mut **self)
    }

    fn end(self) -> Result<(), RecordError> {
        Ok(())
    }
}

impl ser::SerializeStruct for &mut Fields<'_> {
    type Ok = ();
    type Error = RecordError;

    fn serialize_field<T: Serialize + ?Sized>(
        &mut self,
        key: &'static str,
        value: &T,
    ) -> Result<(), RecordError> {
        if self.header {
            self.key = Some(key.to_owned());
        }
        value.serialize(&mut **self)
    }

    fn end(self) -> Result<(), RecordError> {
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// What the csv crate writes for `records`, through one writer.
    fn by_csv<T: Serialize>(records: &[T]) -> csv::Result<Vec<u8>> {
        let mut writer = csv::WriterBuilder::new()
            .has_headers(false)
            .from_writer(Vec::new());
        for r in records {
            writer.serialize(r)?;
        }
        writer.into_inner().map_err(|e| e.into_error().into())
    }

    fn by_records<T: Serialize>(records: &[T]) -> Result<CsvRecords, RecordError> {
        let mut out = CsvRecords::default();
        for r in records {
            out.push(r)?;
        }
        Ok(out)
    }

    #[derive(Serialize)]
    enum Kind {
        Plain,
        #[serde(rename = "with-dash")]
        Dashed,
        Wrapped(f64),
    }

    #[derive(Serialize)]
    struct Unit;

    #[derive(Serialize)]
    struct Inner {
        text: String,
        maybe: Option<f64>,
    }

    #[derive(Serialize)]
    struct Outer {
        name: &'static str,
        inner: Inner,
        kinds: (Kind, Kind, Kind),
        unit: Unit,
        flag: bool,
        n: i64,
        c: char,
        small: f32,
    }

    #[test]
    fn every_kind_of_field_is_written_as_the_csv_crate_writes_it() {
        let texts = [
            "",
            "plain",
            "a,b",
            "say \"hi\"",
            "two\nlines",
            "cr\rlf",
            "#hash",
            " pad ",
            "é",
        ];
        let records: Vec<Outer> = texts
            .iter()
            .enumerate()
            .map(|(i, t)| Outer {
                name: "n",
                inner: Inner {
                    text: t.to_string(),
                    maybe: (i % 2 == 0).then_some(i as f64 * 0.1),
                },
                kinds: (Kind::Plain, Kind::Dashed, Kind::Wrapped(-1e300)),
                unit: Unit,
                flag: i % 3 == 0,
                n: -(i as i64) * 1_000_000_007,
                c: ',',
                small: 1.5e-7,
            })
            .collect();
        let ours = by_records(&records).unwrap();
        assert_eq!(
            String::from_utf8(ours.as_bytes().to_vec()).unwrap(),
            String::from_utf8(by_csv(&records).unwrap()).unwrap()
        );
        assert_eq!(ours.records(), texts.len());
        assert_eq!(
            ours.lines(),
            texts.len() + 1,
            "one record holds a line break"
        );
    }

    #[test]
    fn doubles_are_written_as_ryu_writes_them() {
        let mut edges = vec![
            0.0,
            -0.0,
            1.0,
            0.1 + 0.2,
            1e-4,
            1e-5,
            1e-7,
            1e15,
            9.999_999_999_999_998e15,
            1e16,
            -1e16,
            1.5e16,
            1e21,
            1e22,
            1e300,
            f64::MAX,
            f64::MIN,
            f64::MIN_POSITIVE,
            f64::EPSILON,
            5e-324,
            f64::NAN,
            -f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
        ];
        // Every power of two, and its neighbours: where the shortest text is hardest. Built from
        // their bits: `2f64.powi(e)` below 2^-1023 divides by an overflowed 2^-e and gives zero,
        // which would leave the subnormal powers untested and step below zero's bits.
        for e in -1074i32..1024 {
            let bits = match u32::try_from(e + 1022) {
                Ok(biased) => (u64::from(biased) + 1) << 52,
                Err(_) => 1u64 << (e + 1074),
            };
            edges.extend([
                f64::from_bits(bits),
                f64::from_bits(bits + 1),
                f64::from_bits(bits - 1),
            ]);
        }
        let records: Vec<(f64,)> = edges.iter().map(|&x| (x,)).collect();
        assert_eq!(
            String::from_utf8(by_records(&records).unwrap().into_bytes()).unwrap(),
            String::from_utf8(by_csv(&records).unwrap()).unwrap()
        );
    }

    #[test]
    fn a_record_of_one_empty_field_is_an_empty_quoted_field() {
        let records = [(None::<f64>,), (None,)];
        assert_eq!(by_records(&records).unwrap().as_bytes(), b"\"\"\n\"\"\n");
        assert_eq!(by_csv(&records).unwrap(), b"\"\"\n\"\"\n");
    }

    #[test]
    fn what_csv_refuses_is_refused_and_leaves_nothing() {
        let mut out = CsvRecords::default();
        out.push(&(1.0, 2.0)).unwrap();
        #[derive(Serialize)]
        enum Shape {
            Disc { radius: f64 },
        }
        assert!(out.push(&(3.0, Shape::Disc { radius: 1.0 })).is_err());
        assert!(by_csv(&[(3.0, Shape::Disc { radius: 1.0 })]).is_err());
        assert!(out.push(&(1.0, 2.0, 3.0)).is_err(), "a wider record");
        assert!(by_csv(&[(1.0, 2.0), (1.0, 2.0)]).is_ok());
        assert!(by_csv(&[vec![1.0, 2.0], vec![1.0, 2.0, 3.0]]).is_err());
        assert_eq!(out.as_bytes(), b"1.0,2.0\n");
        assert_eq!((out.records(), out.lines()), (1, 1));
    }

    #[test]
    fn the_header_is_the_csv_crates() {
        #[derive(Serialize)]
        struct Row {
            a: f64,
            #[serde(rename = "b,c")]
            b: Option<u32>,
        }
        let row = Row { a: 1.0, b: None };
        assert_eq!(header_of(&row).unwrap(), b"a,\"b,c\"\n");
        assert_eq!(header_of(&(1.0, 2.0)).unwrap(), b"");
    }

    #[test]
    fn a_flattened_map_gives_its_keys_as_names_and_its_values_as_fields() {
        #[derive(Serialize)]
        struct Row {
            a: f64,
            #[serde(flatten)]
            extra: std::collections::BTreeMap<&'static str, f64>,
            z: &'static str,
        }
        let row = Row {
            a: 1.0,
            extra: [("b", 2.0), ("c", 3.5)].into(),
            z: "x y",
        };
        assert_eq!(header_of(&row).unwrap(), b"a,b,c,z\n");
        let mut out = CsvRecords::default();
        out.push(&row).unwrap();
        assert_eq!(out.as_bytes(), b"1.0,2.0,3.5,x y\n");
    }
}
