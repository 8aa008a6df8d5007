// three.js GLTFLoader plugin for EXT_normal_mesh_compression (ext_spec/README.md).
//
//   const decoder = await EqmeshDecoder.create( { createWasm, draco } );   // EqmeshDecoder.js
//   loader.register( ( parser ) => new GLTFNormalMeshCompressionExtension( parser, decoder,
//       { progressive: true, onLevel: ( mesh, level, info ) => { ... } } ) );
//
// Every mesh with a compressed primitive is built here (GLTFLoader has no
// per-primitive hook): the stream is decoded to positions, unit normals, indices
// and, for a stream with an atlas, TEXCOORD_0 (three.js' 'uv'), and the
// placeholder accessors are never read. With `progressive` the
// coarsest level is built first and each finer level then replaces the geometry in
// place (clones made by GLTFLoader share it), fetching only the bytes that level
// needs: HTTP Range requests for a stream in an external buffer, slices of the
// already-fetched buffer otherwise (a GLB, a data: URI, a server without ranges).
//
// Errors name the mesh and primitive ("mesh 0 primitive 0: CORRUPT_STREAM: ...").
// One that happens before the first level rejects the load; one during progressive
// refinement empties that primitive's geometry (ext_spec Conformance 3: not drawn,
// in every clone) and goes to onError.
import { BufferAttribute, BufferGeometry, Group, Line, LineLoop, LineSegments, LoaderUtils, Mesh,
	MeshStandardMaterial, Points } from 'three';

export const EXTENSION_NAME = 'EXT_normal_mesh_compression';
const MAX_LEVELS = 12; // validity rule 9
const EMBEDDED_CODER = 1; // coder 1 (zerotree): one payload in range 1, ranges 2..J empty

export class GLTFNormalMeshCompressionExtension {

	// options: progressive (false), maxLevel (-1: all), maxTriangles (default: each
	// primitive's recorded triangleBudget, its source's triangle count; 0: none),
	// onLevel(mesh, level, info), onError(error, mesh) (default console.error).
	constructor( parser, decoder, options = {} ) {

		this.name = EXTENSION_NAME;
		this.parser = parser;
		this.decoder = decoder;
		this.progressive = options.progressive === true;
		this.maxLevel = Number.isInteger( options.maxLevel ) ? options.maxLevel : - 1;
		this.maxTriangles = Number.isInteger( options.maxTriangles ) && options.maxTriangles >= 0 ? options.maxTriangles : - 1;
		this.onLevel = options.onLevel || null;
		this.onError = options.onError || ( ( error ) => console.error( error ) );
		// BufferGeometry -> PrimitiveStream: GLTFLoader's clones share the geometry, so
		// setLevel works on any of them.
		this._streams = new WeakMap();
		this._defaultMaterial = null;

	}

	loadMesh( meshIndex ) {

		const meshDef = this.parser.json.meshes[ meshIndex ];
		if ( ! meshDef.primitives.some( ( p ) => p.extensions && p.extensions[ EXTENSION_NAME ] ) ) return null;
		return this._loadMesh( meshIndex, meshDef );

	}

	// Shows `level` of a mesh this plugin built, or of a clone (fetching what it
	// lacks); resolves to the same info onLevel receives.
	async setLevel( mesh, level ) {

		const stream = this._streams.get( mesh.geometry );
		if ( ! stream ) throw new Error( `${mesh.name}: not an ${EXTENSION_NAME} primitive` );
		return stream.show( level );

	}

	// Level count J of a mesh this plugin built (or of a clone), or -1.
	levelsOf( mesh ) {

		const stream = this._streams.get( mesh.geometry );
		return stream ? stream.ext.levels : - 1;

	}

	async _loadMesh( meshIndex, meshDef ) {

		if ( ! this.decoder ) throw new Error( `${EXTENSION_NAME}: no EqmeshDecoder given to the plugin` );
		const primitives = meshDef.primitives;
		const streams = primitives.map( ( p, i ) => this._streamFor( meshIndex, i, p ) );
		const [ materials, geometries ] = await Promise.all( [
			Promise.all( primitives.map( ( p ) => this._material( p ) ) ),
			Promise.all( primitives.map( ( p, i ) => streams[ i ] ? streams[ i ].first() : this._plainGeometry( p ) ) ),
		] );
		const meshes = primitives.map( ( p, i ) => this._object( meshIndex, meshDef, i, geometries[ i ], materials[ i ] ) );
		streams.forEach( ( s, i ) => s && this._track( s, meshes[ i ] ) );
		return meshes.length === 1 ? meshes[ 0 ] : this._group( meshIndex, meshes );

	}

	_streamFor( meshIndex, primitiveIndex, primitive ) {

		if ( ! primitive.extensions || ! primitive.extensions[ EXTENSION_NAME ] ) return null;
		return new PrimitiveStream( this, meshIndex, primitiveIndex, primitive );

	}

	_track( stream, mesh ) {

		this._streams.set( mesh.geometry, stream );
		stream.mesh = mesh;
		if ( this.onLevel ) this.onLevel( mesh, stream.shown.level, stream.shown );
		if ( this.progressive ) stream.refine();

	}

	_material( primitive ) {

		if ( primitive.material !== undefined ) return this.parser.getDependency( 'material', primitive.material );
		// glTF 2.0's default material (§3.9.6): white, fully metallic and rough.
		this._defaultMaterial ||= new MeshStandardMaterial( { color: 0xffffff, metalness: 1, roughness: 1 } );
		return this._defaultMaterial;

	}

	async _plainGeometry( primitive ) {

		return ( await this.parser.loadGeometries( [ primitive ] ) )[ 0 ];

	}

	_object( meshIndex, meshDef, primitiveIndex, geometry, material ) {

		const mode = meshDef.primitives[ primitiveIndex ].mode;
		const Type = { 0: Points, 1: LineSegments, 2: LineLoop, 3: Line }[ mode ] || Mesh;
		const object = new Type( geometry, material );
		object.name = this.parser.createUniqueName( meshDef.name || 'mesh_' + meshIndex );
		if ( meshDef.extras && typeof meshDef.extras === 'object' ) Object.assign( object.userData, meshDef.extras );
		this.parser.assignFinalMaterial( object );
		this.parser.associations.set( object, { meshes: meshIndex, primitives: primitiveIndex } );
		return object;

	}

	_group( meshIndex, meshes ) {

		const group = new Group();
		this.parser.associations.set( group, { meshes: meshIndex } );
		meshes.forEach( ( m ) => group.add( m ) );
		return group;

	}

}

// One compressed primitive: its validated extension object, where its bytes come
// from, and the level on show.
class PrimitiveStream {

	constructor( plugin, meshIndex, primitiveIndex, primitive ) {

		this.plugin = plugin;
		this.where = `mesh ${meshIndex} primitive ${primitiveIndex}`;
		this.primitive = primitive;
		this.ext = null;
		this.source = null;
		this.geometry = null;
		this.mesh = null; // the object GLTFLoader got, for the callbacks
		this.shown = null;
		this._checkedHeader = false;
		this._refineFailed = false;
		this._queue = Promise.resolve();

	}

	// The geometry of the first level to show; any problem rejects (and so fails the load).
	async first() {

		try {

			this.ext = checkExtension( this.plugin.parser.json, this.primitive );
			this.source = new StreamSource( this.plugin.parser, this.ext.bufferView );
			this.geometry = new BufferGeometry();
			const { progressive, maxLevel } = this.plugin;
			const target = maxLevel < 0 ? this.ext.levels : Math.min( maxLevel, this.ext.levels );
			await this._decodeInto( progressive ? 0 : target );
			return this.geometry;

		} catch ( error ) {

			throw this._named( error );

		}

	}

	// Each finer level in turn, up to maxLevel, replacing the geometry as it arrives.
	refine() {

		const last = this.plugin.maxLevel < 0 ? this.ext.levels : Math.min( this.plugin.maxLevel, this.ext.levels );
		for ( let level = this.shown.level + 1; level <= last; level ++ ) {

			this._enqueue( () => this._showOrHide( level ) );

		}

	}

	show( level ) {

		return this._enqueue( async () => {

			try {

				return await this._decodeAndReport( level );

			} catch ( error ) {

				throw this._named( error );

			}

		} );

	}

	// One decode at a time per primitive, in request order.
	_enqueue( task ) {

		const run = this._queue.then( task );
		this._queue = run.catch( () => {} );
		return run;

	}

	// After one failure the finer levels would fail alike: report once, stop refining.
	async _showOrHide( level ) {

		if ( this._refineFailed ) return;
		try {

			await this._decodeAndReport( level );

		} catch ( error ) {

			this._refineFailed = true;
			this.geometry.setDrawRange( 0, 0 );
			this.plugin.onError( this._named( error ), this.mesh );

		}

	}

	async _decodeAndReport( level ) {

		await this._decodeInto( level );
		this.geometry.setDrawRange( 0, Infinity );
		if ( this.plugin.onLevel ) this.plugin.onLevel( this.mesh, level, this.shown );
		return this.shown;

	}

	async _decodeInto( level ) {

		if ( ! Number.isInteger( level ) || level < 0 || level > this.ext.levels ) {

			throw coded( 'INVALID_ARGUMENT', `level ${level} is not in [0, ${this.ext.levels}]` );

		}
		const bytes = await this.source.prefix( prefixEnd( this.ext.levelByteRanges, level ) );
		this._checkHeader( bytes );
		const start = performance.now();
		const budget = this.plugin.maxTriangles >= 0 ? this.plugin.maxTriangles : ( this.ext.triangleBudget || 0 );
		const decoded = this.plugin.decoder.decode( bytes, level, budget );
		const decodeMs = performance.now() - start;
		// The placeholders describe the whole level J, which a budget may cut.
		const json = this.plugin.parser.json;
		const whole = budget === 0 || budget >= json.accessors[ this.primitive.indices ].count / 3;
		if ( level === this.ext.levels && whole ) checkFullCounts( json, this.primitive, this.ext, decoded );
		fillGeometry( this.geometry, decoded );
		this.shown = summary( this.ext, level, decoded, bytes.byteLength, decodeMs );

	}

	// Rules 10 (coder half) and 11 (header agrees with the JSON), once per stream.
	_checkHeader( bytes ) {

		if ( this._checkedHeader ) return;
		checkAgainstHeader( this.ext, this.plugin.decoder.readInfo( bytes ) );
		this._checkedHeader = true;

	}

	_named( error ) {

		if ( error.eqmeshWhere ) return error;
		const named = new Error( `${this.where}: ${error.codeName ? '' : 'INTERNAL: '}${error.message}` );
		named.code = error.codeName || 'INTERNAL';
		named.eqmeshWhere = this.where;
		named.cause = error;
		return named;

	}

}

function summary( ext, level, decoded, bytes, decodeMs ) {

	return {
		level,
		levels: ext.levels,
		vertices: decoded.positions.length / 3,
		triangles: decoded.indices.length / 3,
		bytes, // stream bytes this level needed
		streamBytes: prefixEnd( ext.levelByteRanges, ext.levels ),
		decodeMs,
	};

}

// Replaces the arrays in place so every clone of the mesh follows; dispose() first
// lets the renderer free the GPU buffers of the level being replaced.
function fillGeometry( geometry, decoded ) {

	geometry.dispose();
	geometry.setAttribute( 'position', new BufferAttribute( decoded.positions, 3 ) );
	geometry.setAttribute( 'normal', new BufferAttribute( decoded.normals, 3 ) );
	if ( decoded.texcoords ) geometry.setAttribute( 'uv', new BufferAttribute( decoded.texcoords, 2 ) );
	else geometry.deleteAttribute( 'uv' );
	geometry.setIndex( new BufferAttribute( decoded.indices, 1 ) );
	geometry.computeBoundingBox();
	geometry.computeBoundingSphere();

}

// An Error shaped like EqmeshError: the code name leads the message.
function coded( codeName, message ) {

	const error = new Error( `${codeName}: ${message}` );
	error.codeName = codeName;
	return error;

}

function prefixEnd( ranges, level ) {

	return ranges[ level ][ 0 ] + ranges[ level ][ 1 ];

}

// ---------------------------------------------------------------------------
// Where the stream's bytes come from.

class StreamSource {

	constructor( parser, viewIndex ) {

		this.parser = parser;
		this.viewIndex = viewIndex;
		const view = parser.json.bufferViews[ viewIndex ];
		const buffer = parser.json.buffers[ view.buffer ];
		this.length = view.byteLength;
		this.start = view.byteOffset || 0;
		this.url = isExternal( buffer ) ? this._resolve( buffer.uri ) : null;
		this.bytes = null; // Uint8Array of the view as far as fetched
		this.have = 0;

	}

	// The first `end` bytes of the view.
	async prefix( end ) {

		if ( end > this.have ) await ( this.url ? this._fetchRange( end ) : this._wholeView() );
		return this.bytes.subarray( 0, end );

	}

	async _wholeView() {

		const data = await this.parser.getDependency( 'bufferView', this.viewIndex );
		this.bytes = new Uint8Array( data );
		this.have = this.bytes.byteLength;

	}

	async _fetchRange( end ) {

		const first = this.start + this.have;
		const response = await fetch( this.url, this._request( first, this.start + end - 1 ) ).catch( ( e ) => {

			throw coded( 'IO_ERROR', `${this.url}: ${e.message}` );

		} );
		if ( response.status === 206 && rangeStart( response ) === first ) {

			this._append( new Uint8Array( await response.arrayBuffer() ), end );

		} else if ( response.status === 200 ) {

			// The server ignored the range: keep the whole view and ask no more.
			const all = new Uint8Array( await response.arrayBuffer() );
			this._keepWhole( all.subarray( this.start, this.start + this.length ) );

		} else {

			throw coded( 'IO_ERROR', `${this.url}: HTTP ${response.status}` );

		}

	}

	_append( chunk, end ) {

		if ( chunk.byteLength < end - this.have ) throw coded( 'IO_ERROR', `${this.url}: short range response` );
		if ( ! this.bytes ) this.bytes = new Uint8Array( this.length );
		this.bytes.set( chunk.subarray( 0, end - this.have ), this.have );
		this.have = end;

	}

	_keepWhole( view ) {

		if ( view.byteLength < this.length ) throw coded( 'IO_ERROR', `${this.url}: buffer shorter than its bufferView` );
		this.bytes = view;
		this.have = this.length;

	}

	_request( first, last ) {

		const options = this.parser.options;
		const headers = { ...( options.requestHeader || {} ), Range: `bytes=${first}-${last}` };
		const useCredentials = options.withCredentials || options.crossOrigin === 'use-credentials';
		return { headers, credentials: useCredentials ? 'include' : 'same-origin' };

	}

	_resolve( uri ) {

		const options = this.parser.options;
		const url = LoaderUtils.resolveURL( uri, options.path || '' );
		return options.manager ? options.manager.resolveURL( url ) : url;

	}

}

function isExternal( buffer ) {

	return typeof buffer.uri === 'string' && ! buffer.uri.startsWith( 'data:' ) && ! buffer.uri.startsWith( 'blob:' );

}

function rangeStart( response ) {

	const match = /^bytes (\d+)-/.exec( response.headers.get( 'Content-Range' ) || '' );
	return match ? Number( match[ 1 ] ) : - 1;

}

// ---------------------------------------------------------------------------
// Validity rules (ext_spec "Validity rules"); each failure is an Error whose
// message says which rule.

function checkExtension( json, primitive ) {

	const ext = primitive.extensions[ EXTENSION_NAME ];
	const required = ( json.extensionsRequired || [] ).includes( EXTENSION_NAME );
	if ( ! ( json.extensionsUsed || [] ).includes( EXTENSION_NAME ) ) invalid( 'the extension is not in extensionsUsed (rule 1)' );
	checkPrimitiveShape( primitive, ext );
	checkLevels( ext );
	if ( ext.triangleBudget !== undefined && ! ( Number.isInteger( ext.triangleBudget ) && ext.triangleBudget >= 1 ) ) {

		invalid( 'triangleBudget is not a positive integer' );

	}
	checkAccessors( json, primitive, ext, required );
	checkStreamView( json, ext );
	return ext;

}

function invalid( message ) {

	throw coded( 'INVALID_GLTF', message );

}

function checkPrimitiveShape( primitive, ext ) {

	if ( primitive.mode !== undefined && primitive.mode !== 4 ) invalid( 'mode is not TRIANGLES (rule 2)' );
	const attributes = Object.keys( primitive.attributes || {} );
	const extra = attributes.find( ( a ) => a !== 'POSITION' && a !== 'NORMAL' && a !== 'TEXCOORD_0' );
	if ( extra ) invalid( `attribute ${extra} is not allowed on a compressed primitive (rule 3)` );
	if ( primitive.targets !== undefined ) invalid( 'morph targets are not allowed (rule 3)' );
	if ( primitive.indices === undefined ) invalid( 'indices are missing (rule 4)' );
	const mine = ext.attributes || {};
	if ( mine.POSITION === undefined || mine.POSITION !== primitive.attributes.POSITION ) {

		invalid( 'attributes.POSITION differs from the primitive\'s POSITION (rule 5)' );

	}
	if ( mine.NORMAL !== primitive.attributes.NORMAL ) invalid( 'attributes.NORMAL differs from the primitive\'s NORMAL (rule 5)' );
	if ( mine.TEXCOORD_0 !== primitive.attributes.TEXCOORD_0 ) {

		invalid( 'attributes.TEXCOORD_0 differs from the primitive\'s TEXCOORD_0 (rule 5)' );

	}

}

function checkLevels( ext ) {

	const J = ext.levels;
	if ( ! Number.isInteger( J ) || J < 0 || J > MAX_LEVELS ) invalid( `levels is not an integer in [0, ${MAX_LEVELS}] (rule 9)` );
	const ranges = ext.levelByteRanges;
	if ( ! Array.isArray( ranges ) || ranges.length !== J + 1 ) invalid( `levelByteRanges does not have levels + 1 = ${J + 1} entries (rule 9)` );
	let expected = 0;
	ranges.forEach( ( r, j ) => {

		const ok = Array.isArray( r ) && r.length === 2 && r.every( ( n ) => Number.isSafeInteger( n ) && n >= 0 );
		if ( ! ok ) invalid( `levelByteRanges[${j}] is not a pair of non-negative integers (rule 9)` );
		if ( r[ 0 ] !== expected ) invalid( `levelByteRanges[${j}] starts at ${r[ 0 ]}, expected ${expected} (rule 10)` );
		if ( j < 2 && r[ 1 ] === 0 ) invalid( `levelByteRanges[${j}] is empty (rule 10)` );
		expected = r[ 0 ] + r[ 1 ];

	} );

}

function checkAccessors( json, primitive, ext, required ) {

	const accessors = json.accessors || [];
	const check = ( index, what, type, componentTypes ) => {

		const a = accessors[ index ];
		if ( ! a ) invalid( `${what} accessor ${index} does not exist` );
		if ( a.type !== type || ! componentTypes.includes( a.componentType ) ) invalid( `${what} accessor has the wrong type (rule 6)` );
		if ( required && ( a.bufferView !== undefined || a.sparse !== undefined ) ) {

			invalid( `${what} placeholder accessor has data although the extension is required (rule 7)` );

		}

	};
	check( primitive.attributes.POSITION, 'POSITION', 'VEC3', [ 5126 ] );
	if ( primitive.attributes.NORMAL !== undefined ) check( primitive.attributes.NORMAL, 'NORMAL', 'VEC3', [ 5126 ] );
	if ( primitive.attributes.TEXCOORD_0 !== undefined ) check( primitive.attributes.TEXCOORD_0, 'TEXCOORD_0', 'VEC2', [ 5126 ] );
	check( primitive.indices, 'indices', 'SCALAR', [ 5123, 5125 ] );

}

function checkStreamView( json, ext ) {

	const view = ( json.bufferViews || [] )[ ext.bufferView ];
	if ( ! view ) invalid( `bufferView ${ext.bufferView} does not exist` );
	if ( view.byteStride !== undefined || view.target !== undefined ) invalid( 'the stream\'s bufferView has a byteStride or target (rule 8)' );
	const end = prefixEnd( ext.levelByteRanges, ext.levels );
	if ( end !== view.byteLength ) invalid( `levelByteRanges end at ${end} but the bufferView holds ${view.byteLength} bytes (rule 10)` );
	if ( ! ( json.buffers || [] )[ view.buffer ] ) invalid( `bufferView ${ext.bufferView} refers to a missing buffer` );

}

function checkAgainstHeader( ext, info ) {

	if ( info.levelsInStream !== ext.levels ) invalid( `the stream has ${info.levelsInStream} levels, the JSON says ${ext.levels} (rule 11)` );
	ext.levelByteRanges.forEach( ( r, j ) => {

		if ( r[ 1 ] !== info.chunkLengths[ j ] ) {

			invalid( `levelByteRanges[${j}] length ${r[ 1 ]} differs from the stream's ${info.chunkLengths[ j ]} bytes (rule 11)` );

		}
		if ( j >= 2 && r[ 1 ] === 0 && info.coder !== EMBEDDED_CODER ) {

			invalid( `levelByteRanges[${j}] is empty, which only coder ${EMBEDDED_CODER} streams allow (rule 10)` );

		}

	} );

}

function checkFullCounts( json, primitive, ext, decoded ) {

	if ( ( decoded.texcoords !== null ) !== ( primitive.attributes.TEXCOORD_0 !== undefined ) ) {

		invalid( 'TEXCOORD_0 is declared exactly when the stream has an atlas (rule 5)' );

	}
	const vertices = decoded.positions.length / 3;
	const position = json.accessors[ primitive.attributes.POSITION ];
	const indices = json.accessors[ primitive.indices ];
	if ( position.count !== vertices ) invalid( `POSITION count ${position.count} differs from the ${vertices} decoded vertices (rule 11)` );
	if ( indices.count !== decoded.indices.length ) {

		invalid( `indices count ${indices.count} differs from the ${decoded.indices.length} decoded indices (rule 11)` );

	}

}
